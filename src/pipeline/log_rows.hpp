// Internal: one log (FitRequest::rows and rest_rows): the rows fitted and the rest segment taken
// from the data files themselves, in memory, for fit_files, compare and hexapod identify.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "spdfit/fit_files.hpp"
#include "spdfit/fit_request.hpp"

namespace spdfit::detail {

/// Keeps the rows of A and B (read whole from `source`, a_cols and b_cols applied) that
/// request.rows chooses, or without it those that request.rest_rows does not; with rest_rows,
/// `options`' noise model becomes that of those rows (NoiseModel::from_rest: Sigma_A and Sigma_B
/// their sample covariances). Nothing changes when neither is given. Returns the warnings (rows
/// shared by both). OptionError for a bad selection; DataError naming `source` for a row beyond
/// the file's, no rows left to fit, or a rest segment the model refuses (fewer than 2 rows).
std::vector<Warning> apply_log_rows(const FitRequest& request, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                    const std::string& source, FitOptions& options);

/// fit_files' fit in memory of data already read: the method's checks, the fit, and the
/// readers' names and warnings in the result.
FitResult fit_pair_in_memory(DataPair data, const std::string& a_path, const std::string& b_path, Method method,
                             const FitOptions& options);

}  // namespace spdfit::detail
