// Internal: the checks every reader of a data pair A, B makes, with errors that name the files.
// Shared by the in-memory reader (fit_files.cpp) and the streaming one (stream.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/io.hpp"
#include "spdfit/method.hpp"

namespace spdfit::detail {

/// `read` for the data files of a pair: two files (b_path given) take no column selections; one
/// file (b_path empty) takes two, A's and B's. Throws std::invalid_argument otherwise.
const io::ReadOptions& checked_pair_read(const std::string& b_path, const io::ReadOptions& read);

/// A's and B's part of one file's selected columns (io::Table::selected_columns, two selections):
/// their names (when the file had a header) and what they are for reports ("log.csv columns
/// acc1..acc6 (2-7)").
struct SelectionSplit {
  std::vector<std::string> a_names, b_names;
  std::string a_columns, b_columns;
};
SelectionSplit split_selection(const std::string& path, const std::vector<std::string>& names,
                               const std::vector<std::vector<std::size_t>>& selected);

/// The error for data A, read from `a_path`, with fewer rows (samples) than columns: an n x n
/// X needs at least n samples.
io::DataError fewer_samples_than_columns(const std::string& a_path, std::uint64_t rows, std::uint64_t columns);

/// "1 row", "7 rows".
std::string rows_text(std::uint64_t rows);

/// The error for A and B of different numbers of rows, naming B's file: `problem` says how they
/// differ ("B has 3 rows but A (a.csv) has 4"), the rest is the same for every reader.
io::DataError unequal_rows(const std::string& b_path, const std::string& problem);

/// Throws unequal_rows when both counts are known and differ.
void check_same_rows(const std::string& a_path, std::uint64_t rows_a, const std::string& b_path,
                     std::uint64_t rows_b);

/// Throws io::DataError, naming B's file, when A has n columns and B d != n and `method` (when
/// given) needs a square X (non_square_refusal).
void check_method_fits(const std::optional<Method>& method, const std::string& b_path, long long n, long long d);

/// Throws io::DataError, naming A's file, when m rows are too few for `method`
/// (too_few_rows_refusal).
void check_enough_rows_for(Method method, const std::string& a_path, long long m, long long n, long long d);

}  // namespace spdfit::detail
