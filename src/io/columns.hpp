// Column selections (ReadOptions::columns): their syntax, and their columns in a file of known
// columns and header. Internal to src/io; the readers apply them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "spdfit/io.hpp"

namespace spdfit::io::detail {

/// Each selection's columns as 0-based positions in a file of `columns` columns whose header row
/// gave `names` (empty: the file has none; `named` says whether it could have, as text can and
/// .npy cannot). Throws ColumnSelectionError naming `source` for a name not in the header (listing
/// its names), a position beyond the columns, a range backwards, a column selected twice or by two
/// selections.
std::vector<std::vector<std::size_t>> resolve_columns(const std::vector<ColumnSelection>& selections,
                                                      const std::vector<std::string>& names, std::size_t columns,
                                                      bool named, const std::string& source);

/// The selections' columns in the order they give them, concatenated (0-based).
std::vector<std::size_t> concatenated(const std::vector<std::vector<std::size_t>>& chosen);

/// 1-based positions of 0-based ones, per selection (Table::selected_columns).
std::vector<std::vector<std::size_t>> one_based(const std::vector<std::vector<std::size_t>>& chosen);

/// Applies options.columns (when given) to a table read whole from a format without names (.npy,
/// .mat, .npz): its values keep the selected columns, in order.
void select_table_columns(Table* table, const ReadOptions& options, const std::string& source);

}  // namespace spdfit::io::detail
