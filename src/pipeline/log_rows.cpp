// One log's rows: the data rows and the rest segment chosen by `rows`, `rest_rows` and `time_col`,
// and the columns `a_cols` and `b_cols` choose A and B from.
#include "pipeline/log_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "io/row_selection.hpp"
#include "noise/rest_moments.hpp"
#include "pipeline/sentinels.hpp"
#include "spdfit/format.hpp"
#include "spdfit/noise_model.hpp"

namespace spdfit::detail {

Eigen::VectorXd log_time_column(const FitRequest& request, const std::string& path, Eigen::Index rows) {
  if (request.a_cols.empty() || request.b_cols.empty()) {
    throw OptionError("`time_col` is a column of the one log that `a_cols` and `b_cols` choose A and B from: give "
                      "them too",
                      Code::OptionConflict, "time_col");
  }
  if (path == "-") {
    throw OptionError("`time_col` reads the log's time column from its file: give the log as a file, not on standard "
                      "input",
                      Code::OptionConflict, "time_col");
  }
  const io::ColumnSelection selection{request.time_col, "time_col"};
  io::check_column_selection(selection);
  io::ReadOptions read = request.read;
  read.columns = {selection};
  const io::Table table = io::read_table(path, read);
  if (table.values.cols() != 1) {
    throw io::ColumnSelectionError("`time_col` '" + request.time_col + "' selects " +
                                   std::to_string(table.values.cols()) + " columns of " + path + ": give one");
  }
  if (table.values.rows() != rows) {
    throw io::DataError(path, 0, 0,
                        "the time column (`time_col` '" + request.time_col + "') has " +
                            std::to_string(table.values.rows()) + " rows, the data " + std::to_string(rows),
                        Code::DataShape);
  }
  for (Eigen::Index r = 0; r < rows; ++r) {
    if (!std::isfinite(table.values(r, 0))) {
      throw io::DataError(path, 0, 0,
                          "the time column (`time_col` '" + request.time_col + "') is not a number in data row " +
                              std::to_string(r + 1),
                          Code::DataValue);
    }
    if (std::abs(table.values(r, 0)) >= kSentinelMagnitude) {
      // A logger's code in the time column: its row would silently fall in or out of open ranges.
      throw io::DataError(path, 0, 0,
                          "the time column (`time_col` '" + request.time_col + "') holds " +
                              format_number(table.values(r, 0)) + " in data row " + std::to_string(r + 1) +
                              ": a logger's code for an invalid reading, not a time, so that row has no place in "
                              "time ranges; delete it from the log, or select rows by number (`rows` and "
                              "`rest_rows` without `time_col`)",
                          Code::DataValue);
    }
  }
  return table.values.col(0);
}

std::vector<Warning> apply_log_rows(const FitRequest& request, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                    const std::string& source, FitOptions& options, RowNumbers* kept) {
  std::vector<Warning> out;
  if (request.rows.empty() && request.rest_rows.empty()) {
    if (!request.time_col.empty()) {
      throw OptionError("`time_col` gives `rows` and `rest_rows` in its units: give one of them", Code::OptionConflict,
                        "time_col");
    }
    return out;
  }
  const auto m = static_cast<std::uint64_t>(A.rows());
  // With a time column, the selections are ranges of its values, read from the same file.
  Eigen::VectorXd time;
  if (!request.time_col.empty()) time = log_time_column(request, source, A.rows());
  const auto select = [&](const std::string& spec, const char* option) {
    return time.size() > 0 ? io::detail::selected_times(spec, option, time, source)
                           : io::detail::selected_rows(spec, option, m, source);
  };
  std::vector<Eigen::Index> rest;
  if (!request.rest_rows.empty()) rest = select(request.rest_rows, "rest_rows");
  std::vector<Eigen::Index> fitted;
  if (!request.rows.empty()) {
    fitted = select(request.rows, "rows");
    std::size_t shared = 0;
    for (Eigen::Index r : fitted) shared += std::binary_search(rest.begin(), rest.end(), r) ? 1 : 0;
    if (shared > 0) {
      out.push_back(Warning(Code::NoiseModelNotice,
                                     "`rows` and `rest_rows` share " + std::to_string(shared) +
                                         " rows: the rest segment is fitted as data too",
                                     "rows"));
    }
  } else {
    for (Eigen::Index r = 0; r < A.rows(); ++r) {
      if (!std::binary_search(rest.begin(), rest.end(), r)) fitted.push_back(r);
    }
  }
  if (fitted.empty()) {
    throw io::DataError(source, 0, 0,
                        "`rest_rows` '" + request.rest_rows + "' takes every one of the " + std::to_string(m) +
                            " data rows: none is left to fit (give `rows`)",
                        Code::DataShape);
  }
  if (!rest.empty()) {
    const Eigen::MatrixXd rest_a = A(rest, Eigen::all), rest_b = B(rest, Eigen::all);
    try {
      options.noise = LogRestRows::from_rest(rest_a, rest_b);
    } catch (const std::invalid_argument& e) {
      throw io::DataError(source, 0, 0, "`rest_rows` '" + request.rest_rows + "': " + e.what(), Code::NoiseModel);
    }
  }
  A = Eigen::MatrixXd(A(fitted, Eigen::all));
  B = Eigen::MatrixXd(B(fitted, Eigen::all));
  if (kept != nullptr) *kept = std::move(fitted);
  return out;
}

io::ReadOptions log_columns_read(const FitRequest& request) {
  io::ReadOptions read = request.read;
  if (request.a_cols.empty() && request.b_cols.empty()) return read;
  if (request.a_cols.empty() || request.b_cols.empty()) {
    throw OptionError(std::string(find_option(fit_option_table(), "a_cols")->needs_message));
  }
  const io::ColumnSelection a{request.a_cols, "a_cols"}, b{request.b_cols, "b_cols"};
  io::check_column_selection(a);
  io::check_column_selection(b);
  read.columns = {a, b};
  return read;
}

}  // namespace spdfit::detail
