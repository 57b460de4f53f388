// Internal: the estimators on small problems (n <= kSmallProblemMaxN), X only, without heap
// allocation: every matrix is a bounded-size Eigen matrix on the stack. This is the inner loop
// of the Monte Carlo experiments (thousands to millions of 2x2 and 6x6 problems), where the
// dynamic path spent much of its time in malloc and in loops over run-time sizes.
//
// The arithmetic is the public estimators' own (kernels.hpp), so the results agree with
// spdfit::fit to rounding. One difference: m > 4n rows are factored in chunks of 2n rows (a
// TSQR, as TriangularFactor::append does), which changes only rounding.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "factor/basic_reduction.hpp"  // kSmallProblemMaxN
#include "spdfit/method.hpp"

namespace spdfit::detail {

/// Runs `methods` on A, B (m x n each, finite, m >= n, n <= kSmallProblemMaxN) with the default
/// FitOptions: X[i] becomes method i's estimate in the data's units, or an empty matrix where
/// it has none (a numerical failure: SPDE with A rank-deficient, TLS with V22 singular, an
/// estimate that overflows). X's storage is reused from call to call. Returns false, writing
/// nothing, when n > kSmallProblemMaxN, and always in a build without the small-problem kernels
/// (CMake's SPDFIT_SMALL_PROBLEM_KERNELS=OFF). Throws std::invalid_argument for different shapes,
/// m < n, or NaN or Inf in the data.
bool estimate_small(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                    const std::vector<Method>& methods, std::vector<Eigen::MatrixXd>& X);

}  // namespace spdfit::detail
