// Reading a data file a block of rows at a time, for data larger than memory.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/io.hpp"

namespace spdfit::io {

class RowReader;

namespace detail {
class SplitFile;  // a file split among processes (src/io/split_file.hpp) opens readers of its parts
struct KeptText;  // standard input's text kept for a second reading (src/io/kept_text.hpp)
RowReader standard_input_reader(const ReadOptions& options, std::shared_ptr<KeptText> keep);
class NpyRows;    // a C-order .npy file's rows, read by any thread (src/io/npy_rows.hpp)
/// Internal, for the streaming pipeline: the rows of a C-order .npy file named by path, for any
/// thread to read straight into the QR's input; nullptr for other files.
const NpyRows* direct_rows(const RowReader& reader);
/// Internal: counts the next rows (at most max_rows) of a reader with direct_rows() as read
/// without reading them (they are read through direct_rows()) and returns how many.
Eigen::Index skip_rows(RowReader& reader, Eigen::Index max_rows);
}  // namespace detail

/// Reads the matrix in a data file (the formats of read_table: .npy by its magic bytes,
/// delimited text otherwise) a block of rows at a time, in O(block) memory: a .npy file's blocks
/// are read into one reused buffer (C order) or decoded from a mapping (Fortran order), a MATLAB
/// 7.3 variable is read in row ranges, a text file is read in pieces of about
/// `kTextPieceBytes` bytes of whole lines. The rows, their values and every error (naming the
/// file, and for text the line and column) are those of read_table.
class RowReader {
 public:
  /// Bytes of text read at a time (a longer line is read whole, up to kMaxLineBytes).
  static constexpr std::size_t kTextPieceBytes = std::size_t{1} << 20;
  static constexpr std::size_t kMaxLineBytes = std::size_t{1} << 26;

  /// Opens `path`. Throws DataError when it is missing, not a regular file, unreadable, empty,
  /// or (for .npy) has a bad header, dtype or size.
  explicit RowReader(const std::string& path, const ReadOptions& options = {});
  ~RowReader();
  RowReader(RowReader&&) noexcept;
  RowReader& operator=(RowReader&&) noexcept;

  /// Reads the next rows, at most `max_rows` (>= 1), into `rows` (resized to k x columns) and
  /// returns k: max_rows until the end of the file, fewer in the last block, 0 after it. Throws
  /// DataError on bad data (the text is parsed as it is read, so a bad line deep in a file
  /// fails only when reached), and, at the end, when the file held no data rows.
  Eigen::Index read(Eigen::Index max_rows, Eigen::MatrixXd* rows);

  const std::string& path() const;
  /// The number of columns: known after the first read that returned rows.
  Eigen::Index columns() const;
  /// The header row's column names (text files with a header; empty otherwise).
  const std::vector<std::string>& column_names() const;
  /// What the reader decided for the user to know (see Table::warnings), known after the first
  /// read that returned rows.
  const std::vector<Warning>& warnings() const;
  /// With ReadOptions::columns: each selection's columns as 1-based positions in the file (see
  /// Table::selected_columns), known after the first read that returned rows; the rows read hold
  /// them in this order.
  const std::vector<std::vector<std::size_t>>& selected_columns() const;
  /// Rows returned so far.
  std::uint64_t rows_read() const;
  /// The rows the file holds, known before it is read: a .npy file's header, a MATLAB 7.3
  /// variable's size, a file read whole. Nothing for text, which is counted as it is read.
  std::optional<std::uint64_t> rows_declared() const;
  /// How much of the file has been read, in [0, 1]: bytes for text, rows for .npy and files read
  /// whole; 0 when unknown (standard input before its end).
  double fraction_read() const;

 private:
  friend class detail::SplitFile;
  friend RowReader detail::standard_input_reader(const ReadOptions& options, std::shared_ptr<detail::KeptText> keep);
  friend const detail::NpyRows* detail::direct_rows(const RowReader& reader);
  friend Eigen::Index detail::skip_rows(RowReader& reader, Eigen::Index max_rows);
  RowReader() = default;
  struct Source;  // the format-specific part, one kind per file format (row_reader.cpp)
  class NpySource;
  class TextSource;
  class TableSource;
  class MatSource;
  std::unique_ptr<Source> source_;
};

}  // namespace spdfit::io
