// Internal: turning an estimate in the factor's scaled units into a FitResult with its
// diagnostics, in the data's units.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_result.hpp"
#include "spdfit/format.hpp"
#include "factor/basic_reduction.hpp"

namespace spdfit::detail {

/// Builds the result of `method` from the estimate X_s in scaled units (X = X_s 2^(eb - ea)):
/// fills every common diagnostic (ranks, condition numbers, residual, definiteness, area
/// criterion), appends the common warnings, and converts X to the data's units. The
/// method-specific diagnostics already in `diagnostics` are kept.
FitResult finish(Method method, const DynamicReduction& data, const Eigen::MatrixXd& X_s, Diagnostics diagnostics,
                 std::vector<Warning> warnings);

/// A failed result: no estimate, the common diagnostics of the data, and the message.
FitResult failure(Method method, const DynamicReduction& data, std::string message,
                  std::vector<Warning> warnings = {});

/// The area criterion of a symmetric X_s in scaled units (see area_criterion.hpp); nothing
/// when X_s is not positive semidefinite.
std::optional<double> scaled_area_criterion(const DynamicReduction& data, const Eigen::MatrixXd& X_s);
/// The same from X_s's eigendecomposition (eigenvalues ascending, eigenvectors as columns).
std::optional<double> scaled_area_criterion(const DynamicReduction& data, const Eigen::VectorXd& lambda,
                                            const Eigen::MatrixXd& vectors);

/// Numbers in messages: the library's formatter, Precision::Brief by default ("1.5e+08").
using spdfit::format_number;

}  // namespace spdfit::detail
