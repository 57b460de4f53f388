// Internal: one log (FitRequest::rows and rest_rows): the rows fitted and the rest segment taken
// from the data files themselves, in memory, for fit_files, compare and hexapod identify.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_files.hpp"
#include "spdfit/fit_request.hpp"

namespace spdfit::detail {

/// What the rows of a log read whole gave: the rest segment's noise model, and warnings.
struct LogRows {
  std::optional<NoiseModel> noise;
  std::vector<Warning> warnings;
};

/// Keeps the rows of A and B (read whole from `source`, a_cols and b_cols applied) that
/// request.rows chooses, or without it those that request.rest_rows does not; with rest_rows, the
/// noise model of those rows (NoiseModel::from_rest: Sigma_A and Sigma_B their sample
/// covariances). Nothing changes when neither is given. OptionError for a bad selection; DataError
/// naming `source` for a row beyond the file's, no rows left to fit, or a rest segment the model
/// refuses (fewer than 2 rows).
LogRows apply_log_rows(const FitRequest& request, Eigen::MatrixXd& A, Eigen::MatrixXd& B, const std::string& source);

/// fit_files' fit in memory of data already read: `prepare` applied to them and to the options,
/// the method's checks, the fit, and the readers' names and warnings (with prepare's) in the result.
FitResult fit_pair_in_memory(DataPair data, const std::string& a_path, const std::string& b_path, Method method,
                             FitOptions options,
                             const std::function<std::vector<Warning>(DataPair&, FitOptions&)>& prepare);

/// fit_files' fit in memory: A and B read (read_pair), `prepare` applied to them and to the
/// options (a log's rows: apply_log_rows), the method's checks, the fit, and the readers' names and
/// warnings (with prepare's) in the result.
FitResult fit_files_in_memory(const std::string& a_path, const std::string& b_path, Method method, FitOptions options,
                              const io::ReadOptions& read,
                              const std::function<std::vector<Warning>(DataPair&, FitOptions&)>& prepare = {});

}  // namespace spdfit::detail
