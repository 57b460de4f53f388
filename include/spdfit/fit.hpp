// Running an estimator chosen at run time, or all of them on the same data.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "spdfit/fit_result.hpp"
#include "spdfit/method.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// Runs `method` on the reduced data (see the estimator's own header for what it computes).
/// Throws std::invalid_argument when B's columns differ from A's (d != n) and the method needs a
/// square X (non_square_refusal: only ls and tls fit an n x d X), or when tls meets a non-square
/// X with fewer rows than n + d.
FitResult fit(const Reduction& data, Method method);

/// Runs `method` on A X ~= B (A m x n, B m x d). Throws std::invalid_argument on misuse (see
/// least_squares, and the overload above for d != n). With
/// options.bootstrap = N > 0 the result also carries the bootstrap's standard errors, interval
/// and bias (FitResult::bootstrap): N multinomial resamples of the rows of [A B], each a
/// weighted triangular factor (TriangularFactor::append with counts), refitted with the same
/// method on options.threads threads; cost N times the fit's O(m n^2 + n^3), memory O(N n^2).
FitResult fit(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
              Method method, const FitOptions& options = {});

/// Runs every method in kAllMethods (not auto, which runs one of them) on the same data: one QR
/// and reduction for all, and one SVD of [A B] for tls, tls-sym and tls-psd. The results are
/// those of `fit` for each method. For a non-square X (d != n) only the methods that fit one:
/// ls and tls, in that order. With options.robust (the overload on A and B; the one on a reduction
/// refuses it, as reduce does), every method but spde is its own robust fit, as `fit` gives it.
std::vector<FitResult> fit_all(const Reduction& data);
std::vector<FitResult> fit_all(const Eigen::Ref<const Eigen::MatrixXd>& A,
                               const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

}  // namespace spdfit
