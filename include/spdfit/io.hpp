// Reading matrices from data files (delimited text, .npy, MATLAB .mat, NumPy .npz) and writing them back.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "spdfit/outcome.hpp"

namespace spdfit::io {

/// Bad input data: names the source (a file path) and, for text, the 1-based line and column
/// (0 when not applicable). what() is the full message, "SOURCE:LINE:COLUMN: problem", ready
/// to show a user.
class DataError : public std::runtime_error, public Coded {
 public:
  /// `code`: Code::File for a file's own problem (the default), or the data's (Code::DataShape,
  /// Code::NoiseModel, ...) where a file's contents are refused by what they are for.
  DataError(std::string source, std::size_t line, std::size_t column, const std::string& problem,
            Code code = Code::File);
  const std::string& source() const noexcept { return source_; }
  std::size_t line() const noexcept { return line_; }
  std::size_t column() const noexcept { return column_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string source_;
  std::size_t line_;
  std::size_t column_;
  std::string problem_;
};

/// What a first column of row labels (an index, as pandas' to_csv and R's write.csv write one)
/// in delimited text is taken for.
enum class IndexColumn {
  /// Decided from the file: a header whose first cell is empty (",Fx,Fy"; R's "","x") marks the
  /// first column as row labels, which are dropped with a warning; without that mark, a first
  /// column that is exactly 0, 1, 2, ... (row numbers: at least 3 rows and 2 columns, decided on
  /// the first piece of text read) is refused with a DataError, since fitting it as data is
  /// never what was meant. Otherwise the first column is data.
  Auto,
  Drop,  ///< the first column holds row labels (text or numbers): dropped, never parsed
  Keep,  ///< the first column is data, whatever its header or values
  // The names before spdfit's enumerators took one style (docs/changes.md); removed in the next
  // release.
  kAuto [[deprecated("use IndexColumn::Auto")]] = Auto,
  kDrop [[deprecated("use IndexColumn::Drop")]] = Drop,
  kKeep [[deprecated("use IndexColumn::Keep")]] = Keep,
};

/// Whether the first line of delimited text is a header row of column names.
enum class HeaderRow {
  /// Decided from the file: a first line in which no field is a number is a header; so is a first
  /// line of k >= 2 fields that is exactly 0, 1, ..., k - 1 (pandas' header of a frame without
  /// column names, as to_csv(index=False) writes it), taken with a warning. A single field is data.
  Auto,
  Present,  ///< the first line is a header row, whatever it holds
  Absent,   ///< the first line is data (a line of names is then "not a number")
};

/// Columns chosen from a file, as a user writes them: header names ("F1"), 1-based positions ("3";
/// digits are always positions, even where a header's names are digits), inclusive ranges of
/// either by position in the file ("acc1:acc6", "3:8") and comma-separated lists mixing them
/// ("1,3:5,F1"). Positions count every column of the file, a first column of row labels included
/// unless IndexColumn::Drop drops it first.
struct ColumnSelection {
  std::string spec;
  /// The library name of the option that gave it ("a_cols"), for messages: `a_cols`.
  std::string option;
};

/// A column selection that cannot be applied: bad syntax, a name the header does not have, a
/// position beyond the columns, a range backwards, a column in two selections. The message
/// quotes the selection and names its option in backticks (a front end spells it: --a-cols);
/// front ends treat it as a usage error.
class ColumnSelectionError : public std::invalid_argument, public Coded {
 public:
  /// `option`: the library name of the option that gave the selection ("a_cols"), or empty.
  explicit ColumnSelectionError(const std::string& message, std::string option = {})
      : std::invalid_argument(message), Coded(Code::ColumnSelection, std::move(option)) {}
};

/// Checks the syntax of a selection (names, positions, ranges, lists) without a file: throws
/// ColumnSelectionError on an empty item, a range without an end, a backwards range of
/// positions. Names are checked against a file's header when it is read.
void check_column_selection(const ColumnSelection& selection);

/// Options for reading.
struct ReadOptions {
  /// NaN and Inf are rejected unless this is set; with it, an empty field of delimited text (as
  /// pandas' to_csv writes NaN) reads as NaN.
  bool allow_nonfinite = false;
  IndexColumn index_column = IndexColumn::Auto;  ///< delimited text only (.npy has no labels)
  HeaderRow header_row = HeaderRow::Auto;        ///< delimited text only
  /// When given, only these columns are read, in this order: the first selection's columns,
  /// then the second's (no column in two). The other columns are not parsed, so a column of
  /// timestamps or text that is not selected is ignored, and the row-label rules of
  /// `index_column` (Auto) do not apply. .npy, .mat and .npz files have no names: positions only.
  std::vector<ColumnSelection> columns;
};

/// A matrix with the column names of its header row (empty when the file had none).
struct Table {
  Eigen::MatrixXd values;
  std::vector<std::string> column_names;
  /// What the reader decided for the user to know: a first column of row labels dropped, pandas'
  /// header 0, 1, ... taken as column names.
  std::vector<Warning> warnings;
  /// Delimited text: the 1-based line of the first data row (0 for other formats), so that a
  /// caller whose shape check fails can point at a first line that may be a header.
  std::size_t first_data_line = 0;
  /// With ReadOptions::columns: each selection's columns as 1-based positions in the file (values
  /// holds them in this order, and column_names their names).
  std::vector<std::vector<std::size_t>> selected_columns;
};

/// Each selection's columns in a table whose columns are named `names` (a header row, a pandas
/// DataFrame's labels), as 1-based positions, by the rules of ReadOptions::columns: the same
/// selection picks the same columns from a file with that header and from the table. Throws
/// ColumnSelectionError naming `source` for bad syntax, a name not among `names` (listing them),
/// a position beyond them, a range backwards, a column selected twice or by two selections.
std::vector<std::vector<std::size_t>> select_columns(const std::vector<ColumnSelection>& selections,
                                                     const std::vector<std::string>& names, const std::string& source);

/// "columns acc1..acc6 (2-7)", "columns 2, 4, 9", "column F1 (8)": the columns a selection chose,
/// for reports. `positions` are 1-based, `names` their header names (empty without a header).
std::string describe_columns(const std::vector<std::size_t>& positions, const std::vector<std::string>& names);

/// A data file and, for a .mat or .npz file, the array in it ("" when not named).
struct FileSpec {
  std::string file;
  std::string variable;
};

/// Splits "A.mat:accel" into the file and the array's name, as read_table reads it. A path that
/// exists as given is a file whatever its colons; otherwise the part before the last colon names
/// the file when that exists. Anything else is the path as given (whose reader then says "no such
/// file"). Cost: up to two stat calls.
FileSpec split_spec(const std::string& path);

/// Reads a matrix from `path`: a .npy file (recognized by its magic bytes; float64, float32,
/// integers or booleans, C or Fortran order, 1-D read as a column), a MATLAB .mat file (levels 5
/// and 7.3) or a NumPy .npz archive, whose array "file.mat:name" names (without a name: the
/// file's only 2-D numeric array; a file whose own name holds the colon wins when it exists),
/// "-" for standard input, or delimited text. Text: fields separated by commas, semicolons,
/// tabs or runs of spaces; CRLF or LF line ends; an optional UTF-8 byte-order mark; lines whose
/// first non-blank character is '#' or '%' are comments; blank lines are skipped; an optional
/// header row (a first data line in which no field is a number, or pandas' 0, 1, ..., k - 1, as
/// ReadOptions::header_row says) gives the column names; a first column of row labels is dropped
/// or refused as ReadOptions::index_column says.
/// Throws DataError (naming the file, and for text the line and column) on: a missing,
/// unreadable or empty file, a directory, binary garbage, ragged rows, empty fields, a token
/// that is not a number, NaN or Inf (unless allowed), no data rows, a malformed .npy.
Table read_table(const std::string& path, const ReadOptions& options = {});
Eigen::MatrixXd read_matrix(const std::string& path, const ReadOptions& options = {});

/// The shortest decimal text that reads back as exactly `value` ("inf", "-inf", "nan" for
/// non-finite values).
std::string format_double(double value);

/// Writes X as CSV: one matrix row per line, comma-separated, values as format_double.
void write_csv(std::ostream& out, const Eigen::Ref<const Eigen::MatrixXd>& X);
/// Writes X as CSV with names: a header row of column names after an empty first cell, and each
/// row's name in its first column (as pandas' to_csv and R's write.csv write a labelled table;
/// read_table reads it back, dropping the labels). Names are quoted. Throws
/// std::invalid_argument unless there is one name per row and per column.
void write_csv(std::ostream& out, const Eigen::Ref<const Eigen::MatrixXd>& X,
               const std::vector<std::string>& row_names, const std::vector<std::string>& column_names);
/// Writes `text` to `path` as it is. Throws DataError saying why when the file cannot be written
/// ("cannot be written (no such directory)", "(permission denied)", "writing failed (...)").
void write_text(const std::string& path, std::string_view text);
/// Writes X to `path` as CSV. Throws DataError when the file cannot be written.
void write_csv(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& X);
/// Writes X to `path` as a .npy file (float64, C order). Throws DataError on failure.
void write_npy(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& X);
/// Writes X to `path` as a MATLAB level-5 .mat file holding the double matrix `name` (load(path)
/// in MATLAB or scipy.io.loadmat gives it back). Throws DataError on failure.
void write_mat(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& name = "X");

}  // namespace spdfit::io
