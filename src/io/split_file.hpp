// A data file split among K processes by rows (internal: the distributed streaming fit,
// src/pipeline/distributed.cpp). Row i of A goes with row i of B, and the lines of two text files
// differ in length, so the files are split by data rows, not by bytes: each process counts the
// lines of its K-th of a text file's bytes, the counts of all processes give every data row's
// place, and each process then reads the same row range of A and of B. A .npy file's rows
// follow from its header. Other formats cannot be split.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "delimited_parser.hpp"
#include "spdfit/io.hpp"
#include "spdfit/row_reader.hpp"

namespace spdfit::io::detail {

/// floor(total k / parts) without overflow, for 0 <= k <= parts: the start of part k of `total`
/// things split into `parts` nearly equal parts.
constexpr std::uint64_t scaled_share(std::uint64_t total, std::uint64_t k, std::uint64_t parts) {
  return total / parts * k + total % parts * k / parts;
}

/// Where a data row's line starts in a text file.
struct LinePosition {
  std::uint64_t byte = 0;
  std::uint64_t lines_before = 0;  ///< the line's number is lines_before + 1
};

class SplitFile {
 public:
  /// Opens `path` for splitting among `parts` processes, this one being `part` (0-based). A text
  /// file's first lines are parsed here (by every process alike) to learn its layout: separator,
  /// header, columns, index column. Throws DataError as RowReader does, and for a format that
  /// cannot be split (.mat, .npz, standard input) when parts > 1.
  SplitFile(const std::string& path, const ReadOptions& options, int part, int parts);

  /// This process's counts, to be gathered from every process (in part order) and handed to
  /// set_counts: for text, the lines starting in this part's bytes and how many of them have
  /// content (not blank, not a comment); nothing for .npy. Cost: a scan of the part's bytes.
  std::vector<std::uint64_t> count() const;
  /// Every process's count(), in part order.
  void set_counts(const std::vector<std::vector<std::uint64_t>>& counts);
  /// The file's data rows (after set_counts).
  std::uint64_t rows() const { return rows_; }
  /// Its columns (after dropping a label column).
  Eigen::Index columns() const { return columns_; }
  /// With ReadOptions::columns: each selection's columns, 1-based (RowReader::selected_columns).
  const std::vector<std::vector<std::size_t>>& selected_columns() const { return selected_; }
  const std::string& path() const { return path_; }

  /// Where data row `row` (0 <= row <= rows(); rows() is the end of the file) starts. Cost: a
  /// scan of at most one part's bytes (text). Needs set_counts.
  LinePosition locate(std::uint64_t row) const;

  /// A reader of the data rows [first, first + count), which start at `begin` (locate(first)) and
  /// end before `end` (locate(first + count)). count > 0.
  RowReader open(std::uint64_t first, std::uint64_t count, const LinePosition& begin, const LinePosition& end) const;

 private:
  std::string path_;
  ReadOptions options_;
  int part_ = 0;
  int parts_ = 1;
  bool npy_ = false;
  std::uint64_t size_ = 0;  // bytes
  DelimitedParser::Layout layout_;
  Eigen::Index columns_ = 0;
  std::vector<std::vector<std::size_t>> selected_;
  std::uint64_t rows_ = 0;
  std::vector<std::vector<std::uint64_t>> counts_;
};

}  // namespace spdfit::io::detail
