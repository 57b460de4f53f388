// Internal: the numbers of the data rows in their files, for the messages and reports that name
// rows (the sentinel and outlier warnings, the robust fit's rows_downweighted). With `rows` (one
// log) the rows fitted are a part of the file: row i of A is the file's data row numbers[i] + 1.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "spdfit/fit_result.hpp"

namespace spdfit::detail {

/// 0-based data rows of the file, one per row of A and B, ascending; empty: row i is the file's i.
using RowNumbers = std::vector<Eigen::Index>;

/// The 1-based number in its file of row i (0-based) of A and B.
inline std::uint64_t file_row(const RowNumbers& numbers, Eigen::Index i) {
  const Eigen::Index row = numbers.empty() ? i : numbers[static_cast<std::size_t>(i)];
  return static_cast<std::uint64_t>(row) + 1;
}

/// A robust fit's rows_downweighted (1-based rows of A and B) numbered as in the file.
inline void number_rows(RobustReport& report, const RowNumbers& numbers) {
  for (std::uint64_t& row : report.rows_downweighted) row = file_row(numbers, static_cast<Eigen::Index>(row - 1));
}

}  // namespace spdfit::detail
