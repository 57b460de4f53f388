// Estimating from data files: A and B read whole, or streamed a block of rows at a time; the
// one path the command line and Python share.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/method.hpp"
#include "spdfit/stream.hpp"

namespace spdfit {

/// A and B as read from their files.
struct DataPair {
  Eigen::MatrixXd A, B;
  std::vector<Warning> warnings;  ///< the readers' (io::Table::warnings), A's then B's
  std::vector<std::string> a_names, b_names;  ///< the files' column names (empty without a header row)
  /// A and B from one file: the columns each came from (FitResult::a_columns); empty otherwise.
  std::string a_columns, b_columns;
};

/// Reads A and B from `a_path` and `b_path` (the formats of io::read_table) and checks that they
/// have the same number of rows m, with m >= n, A's columns (B's, d, may differ: the n x d X of ls
/// and tls). Throws io::DataError naming the file on bad data, when A has fewer rows than columns
/// (checked before B is read, so that a hostile A with millions of columns costs one file, not
/// two) or when the row counts differ. Memory O(m (n + d)).
/// With an empty `b_path`, A and B are the two column selections of options.columns (A's, then
/// B's: `a_cols` and `b_cols`) in `a_path`'s one file, read once; then io::ColumnSelectionError
/// for a selection the file does not have. std::invalid_argument unless two selections come with
/// one file and none with two.
DataPair read_pair(const std::string& a_path, const std::string& b_path, const io::ReadOptions& options = {});

/// Runs `method` on A X ~= B with A and B in files: read whole with read_pair when `stream` is
/// empty, else a block of rows at a time with stream_factor (memory
/// O(threads * block_rows * n + n^2) for any m); then fit(reduce(factor, options), method). The two
/// paths give the same estimate to rounding. Throws io::DataError on bad data (see read_pair and
/// stream_factor), naming B's file when B's d != n columns meet a method that needs a square X
/// (non_square_refusal), and std::invalid_argument on invalid options; a numerical failure is the
/// result's status. `read` says how the files are read, on either path (it takes the place of
/// stream->read); the readers' warnings come first in the result's warnings, and the files'
/// column names are the result's row_names (A's) and column_names (B's). With an empty `b_path`,
/// A and B are the two column selections of read.columns in `a_path`'s one file (see read_pair),
/// read once on either path; the result's a_columns and b_columns say which. Cost O(m n^2) plus
/// the method's O(n^3).
/// With options.bootstrap and `stream`: the streaming (Poisson) bootstrap on groups of 4096 rows,
/// which needs about 100 groups (409,600 rows). With fewer, the files are read again whole and
/// their rows resampled one at a time in memory (with a warning saying so) when A and B take at
/// most stream->bootstrap_memory_bytes (256 MiB) as doubles. Standard input ("-", one of the two)
/// cannot be read again: its text is kept while it is streamed, up to the same budget, and read
/// from there. Beyond the budget (the doubles, or standard input's text) io::DataError saying how
/// many rows the streaming bootstrap needs.
FitResult fit_files(const std::string& a_path, const std::string& b_path, Method method,
                    const FitOptions& options = {}, const std::optional<StreamOptions>& stream = std::nullopt,
                    const io::ReadOptions& read = {});

}  // namespace spdfit
