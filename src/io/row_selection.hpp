// Internal: row selections ("601:", "1:5000,7001:", "3,8:12"): 1-based inclusive ranges and lists
// of a file's data rows, as FitRequest::rows and rest_rows give them. Parsed and applied in
// memory (io/columns.cpp, beside the column selections).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace spdfit::io::detail {

/// Throws OptionError (Code::OptionValue, naming `option`) when `spec` is not a row selection:
/// an empty item, a range without numbers or running backwards, row 0, text that is not a number.
/// With `by_time`, a selection of row numbers or of times (FitRequest::time_col, perhaps given
/// later): only the syntax is checked, the numbers any finite ones.
void check_row_selection(const std::string& spec, const std::string& option, bool by_time = false);

/// The rows (0-based, ascending, each once) that `spec` keeps of `rows` data rows; a range without
/// an end runs to the last row. OptionError as check_row_selection; DataError naming `source` (the
/// file) when an item reaches beyond the last row.
std::vector<Eigen::Index> selected_rows(const std::string& spec, const std::string& option, std::uint64_t rows,
                                        const std::string& source);

/// The rows (0-based, ascending) whose `time` (a time column's values, one per data row) falls in
/// one of `spec`'s ranges of times ("12.5:60", ":0.995,100:": inclusive; a missing end is open; a
/// single number keeps the rows at exactly that time). OptionError as check_row_selection with
/// by_time; DataError naming `source` when no row's time is in them.
std::vector<Eigen::Index> selected_times(const std::string& spec, const std::string& option,
                                         const Eigen::Ref<const Eigen::VectorXd>& time, const std::string& source);

}  // namespace spdfit::io::detail
