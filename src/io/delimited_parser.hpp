// The delimited-text parser, fed a piece of the text at a time: parse_delimited gives it the
// whole text at once, the streaming RowReader gives it blocks of whole lines read from a file.
// Internal to src/io.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "fields.hpp"
#include "spdfit/io.hpp"

namespace spdfit::io::detail {

class DelimitedParser {
 public:
  /// Data rows the index column is decided on (ReadOptions::index_column): whether the first
  /// column is 0, 1, 2, ...
  static constexpr std::size_t kIndexDecisionRows = 3;

  DelimitedParser(std::string source, ReadOptions options)
      : source_(std::move(source)), options_(options), drop_first_(options.index_column == IndexColumn::Drop) {
    // Selected columns: the others are ignored, so a first column of labels needs no decision.
    if (selecting()) index_decided_ = true;
  }

  /// What a parser decided on a file's first lines, which every later line is parsed by: the
  /// separator, the header, the number of columns and whether the first is dropped as labels.
  struct Layout {
    Separator separator = Separator::None;
    std::size_t separator_line = 0;
    bool have_header = false;
    std::size_t columns = 0;
    std::size_t columns_line = 0;
    bool drop_first = false;
    std::vector<long> slots;  ///< with selected columns: each file column's place in a row, or -1
    std::size_t selected = 0;
    std::vector<std::vector<std::size_t>> selected_columns;
    bool units_row = false;  ///< a second header row (units) under the header, skipped
  };
  /// The layout decided so far: final once a data row has been parsed and the index column decided
  /// (ReadOptions::index_column), which is after the first piece with three data rows.
  Layout layout() const {
    return {separator_, separator_line_, have_header_, columns_, columns_line_, drop_first_, slots_, out_columns_,
            selected_,   units_row_};
  }
  /// A parser for a later part of a file whose first lines decided `layout`: the part starts at a
  /// line start after the file's first data row, with `lines_before` lines and `bytes_before` bytes
  /// before it, so that messages give the file's own line numbers and byte offsets.
  DelimitedParser(std::string source, ReadOptions options, const Layout& layout, std::size_t lines_before,
                  std::size_t bytes_before);

  /// Parses the next piece of the text: it starts where the previous piece ended, at the start
  /// of a line, and ends with a line end or at the end of the input (no line, and no CR LF
  /// pair, is split between two pieces). The values of its data rows are appended to values(),
  /// row by row. Throws DataError naming the source, line and column on bad text.
  void feed(std::string_view text);

  /// Ends the input: throws DataError ("no data rows ...") when there were no data rows.
  void finish() const;

  std::size_t rows() const { return rows_; }        ///< data rows parsed so far
  /// The columns of a row as parsed: the selected ones (ReadOptions::columns), else all; 0 until
  /// the first data row.
  std::size_t columns() const { return selecting() ? out_columns_ : columns_; }
  /// With ReadOptions::columns: each selection's columns, 1-based (Table::selected_columns).
  const std::vector<std::vector<std::size_t>>& selected_columns() const { return selected_; }
  const std::vector<std::string>& column_names() const { return column_names_; }
  /// Keeps the labels of a first column dropped as row labels (an index), one per data row, in
  /// row_names(): for the callers that show them (read_labelled_table).
  void keep_row_labels() { keep_row_labels_ = true; }
  const std::vector<std::string>& row_names() const { return row_names_; }
  /// The text after the source's name of the notice that a first column was dropped as row
  /// labels (read_labelled_table leaves it out when the labels are the column names).
  static constexpr const char* kIndexColumnNotice = ": the first column holds row labels";
  /// What the parser decided for the user to know (a first column of row labels dropped).
  const std::vector<Warning>& warnings() const { return warnings_; }
  /// The values of the rows parsed since the caller last cleared them, row-major.
  std::vector<double>& values() { return values_; }
  const std::vector<double>& values() const { return values_; }
  std::size_t lines() const { return line_number_; }  ///< lines parsed so far
  /// The 1-based line of the first data row (0 before it, and in a parser built from a Layout).
  std::size_t first_data_line() const { return first_data_line_; }

 private:
  // One line of the text, without its line end.
  struct Line {
    std::string_view raw;
    std::string_view content;  // raw without leading and trailing blanks
    std::size_t number = 0;    // 1-based
  };

  void check_is_text(std::string_view text, bool first_piece) const;
  bool next_line(Line* line);
  void parse_line(const Line& line);
  void keep_header(const Line& line);
  void decide_index_column();
  bool next_field(const Line& line, FieldSplitter* splitter, Field* field) const;
  bool is_header(const Line& line, Separator separator) const;
  bool header_first_cell_empty(const Line& line) const;
  struct FieldKinds {
    std::size_t fields = 0, text = 0, numbers = 0;
  };
  FieldKinds field_kinds(const Line& line) const;
  bool is_units_row(const Line& line) const;
  void note_empty_rows();
  bool counts_columns(const Line& line, std::size_t start = 0, bool* all_quoted = nullptr) const;
  std::string abbreviated_count(const Line& line, std::size_t start = 0) const;
  void choose_separator_after_header(const Line& data);
  std::vector<std::string> header_names(std::size_t data_fields) const;
  std::size_t parse_row(const Line& line);
  bool selecting() const { return !options_.columns.empty(); }
  void select_columns(const Line& first_row);
  double parse_value(const Line& line, const Field& field) const;
  [[noreturn]] void fail_empty_field(const Line& line, const Field& field, std::size_t index) const;
  [[noreturn]] void fail_not_a_number(const Line& line, const Field& field) const;
  std::string separator_origin() const;
  /// "; column N is selected by `--b-cols` 'F1:F6'" for the field being parsed, when columns are
  /// selected; else empty.
  std::string selected_column_note() const;
  [[noreturn]] void fail(const Line& line, std::size_t offset, const std::string& problem) const;

  std::string source_;
  ReadOptions options_;

  std::string_view text_;  // the piece being parsed (after the byte-order mark)
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
  std::size_t bytes_fed_ = 0;     // bytes of all pieces so far
  std::size_t piece_offset_ = 0;  // where text_ starts in the input
  bool any_text_ = false;

  Separator separator_ = Separator::None;
  std::size_t separator_line_ = 0;  // the line that decided separator_
  bool seen_content_ = false;
  bool have_header_ = false;
  std::string header_raw_;  // the header line, owned: it may be in an earlier piece
  Line header_;
  std::size_t rows_ = 0;
  std::size_t columns_ = 0;
  std::size_t columns_line_ = 0;
  std::vector<std::string> column_names_;
  bool keep_row_labels_ = false;
  std::vector<std::string> row_names_;
  std::vector<double> values_;  // row-major

  // The first column as row labels (ReadOptions::index_column): dropped when drop_first_; in
  // kAuto mode, whether the first column has been 0, 1, 2, ... so far, until decided.
  bool drop_first_ = false;
  bool index_decided_ = false;
  bool first_column_counts_rows_ = true;
  std::size_t first_data_line_ = 0;
  std::vector<Warning> warnings_;
  bool resumed_ = false;  // built from a Layout: the first lines were parsed elsewhere
  // Lines of separators only (a spreadsheet's empty rows) since the last data row, and those
  // between data rows (note_empty_rows).
  static constexpr std::size_t kNamedEmptyRows = 5;
  std::size_t empty_rows_pending_ = 0;
  std::vector<std::size_t> empty_rows_pending_lines_;  // the first few, while kNamedEmptyRows are not named
  std::vector<std::size_t> empty_rows_named_;          // the first few of those between data rows
  std::size_t empty_rows_between_ = 0;
  std::size_t empty_rows_notice_ = 0;  // 1 + the notice's index in warnings_, or 0
  bool units_row_ = false;  // the line after the header was a units row, skipped
  std::size_t units_line_ = 0;

  // ReadOptions::columns, decided at the first data row: each file column's place in a row of
  // values (-1: not selected, not parsed), the selected count, the selections' 1-based columns;
  // the column being parsed (0-based, for messages).
  std::vector<long> slots_;
  std::size_t out_columns_ = 0;
  std::vector<std::vector<std::size_t>> selected_;
  std::size_t current_column_ = 0;
};

/// parse_delimited, and the labels of a first column dropped as row labels in `row_names` (one
/// per data row; not kept when null).
Table parse_delimited_labelled(std::string_view text, const std::string& source, const ReadOptions& options,
                               std::vector<std::string>* row_names);

}  // namespace spdfit::io::detail
