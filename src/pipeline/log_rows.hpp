// Internal: one log (FitRequest::rows and rest_rows): the rows fitted and the rest segment taken
// from the data files themselves, in memory, for fit_files, compare and hexapod identify.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/row_numbers.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/fit_request.hpp"

namespace spdfit::detail {

struct Replicate;  // uncertainty/bootstrap.hpp

/// Keeps the rows of A and B (read whole from `source`, a_cols and b_cols applied) that
/// request.rows chooses, or without it those that request.rest_rows does not; with rest_rows,
/// `options`' noise model becomes that of those rows (NoiseModel::from_rest: Sigma_A and Sigma_B
/// their sample covariances). With request.time_col the selections are ranges of the time column's
/// values, read from `source` (a file; with a_cols and b_cols). Nothing changes when neither is
/// given. Returns the warnings (rows shared by both); `kept`, when given, receives the rows fitted
/// (0-based data rows of the file, for the messages that name rows; empty when all are).
/// OptionError for a bad selection; DataError naming `source` for a row beyond the file's, no rows
/// left to fit, or a rest segment the model refuses (fewer than 2 rows).
std::vector<Warning> apply_log_rows(const FitRequest& request, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                    const std::string& source, FitOptions& options, RowNumbers* kept = nullptr);

/// The time column (request.time_col) of the log at `path`, read with request.read: `rows` values
/// (the data's rows). OptionError without a_cols and b_cols; io::ColumnSelectionError for a
/// selection that is not one column of the file; io::DataError naming the file for a count that
/// differs or a value that is not finite.
Eigen::VectorXd log_time_column(const FitRequest& request, const std::string& path, Eigen::Index rows);

/// fit_files' fit in memory of data already read: the method's checks, the fit, and the
/// readers' names and warnings in the result; rows named as `numbers` numbers them.
FitResult fit_pair_in_memory(DataPair data, const std::string& a_path, const std::string& b_path, Method method,
                             const FitOptions& options, const RowNumbers& numbers = {});

/// request.read with one log's column selections (a_cols, then b_cols) when they are given, for
/// the data and the rest files alike. OptionError for one without the other or a bad selection.
io::ReadOptions log_columns_read(const FitRequest& request);

/// fit(A, B, method, options) of rows numbered in their file by `numbers` (the rows a warning or
/// the robust fit's report names).
FitResult fit_numbered(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                       Method method, const FitOptions& options, const RowNumbers& numbers);

/// With options.robust, each result in `results` of a method that weighs rows (all but spde)
/// replaced by its own robust fit of A and B (robust_fit, its offsets those of its weighted rows),
/// rows named as `numbers` numbers them: compare's and hexapod identify's robust estimators. With
/// options.bootstrap each robust fit has its own (robust_fit's: every resample refitted robustly);
/// `replicates`, when given, receives each result's replicates (empty for a result not refitted).
void refit_robustly(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                    const FitOptions& options, std::vector<FitResult>& results, const RowNumbers& numbers,
                    std::vector<std::vector<Replicate>>* replicates = nullptr);

/// The warning of rows that dominate the fit of `method` (dominant_rows_warning), as fit would
/// give it, for the commands that fit several methods at once (compare, hexapod identify): said
/// once, judged by one method's residuals (auto's). Nothing where that fit fails.
std::optional<Warning> dominant_rows_check(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                           const Eigen::Ref<const Eigen::MatrixXd>& B, Method method,
                                           const FitOptions& options, const RowNumbers& numbers);

}  // namespace spdfit::detail
