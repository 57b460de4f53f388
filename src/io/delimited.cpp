// The delimited-text reader: CSV, semicolon-separated (European spreadsheets), tab-separated,
// and space-aligned columns (MATLAB's save -ascii).
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "columns.hpp"
#include "delimited_parser.hpp"
#include "fields.hpp"
#include "parse.hpp"
#include "spdfit/io.hpp"
#include "text_scan.hpp"

namespace spdfit::io {

namespace {

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// `text` without the spaces and tabs around it.
std::string_view trimmed(std::string_view text) {
  std::size_t first = 0;
  std::size_t last = text.size();
  while (first < last && is_blank(text[first])) ++first;
  while (last > first && is_blank(text[last - 1])) --last;
  return text.substr(first, last - first);
}

}  // namespace

namespace detail {

DelimitedParser::DelimitedParser(std::string source, ReadOptions options, const Layout& layout,
                                 std::size_t lines_before, std::size_t bytes_before)
    : source_(std::move(source)), options_(options), drop_first_(layout.drop_first) {
  line_number_ = lines_before;
  bytes_fed_ = bytes_before;
  separator_ = layout.separator;
  separator_line_ = layout.separator_line;
  seen_content_ = true;
  have_header_ = layout.have_header;
  columns_ = layout.columns;
  columns_line_ = layout.columns_line;
  index_decided_ = true;
  resumed_ = true;
  slots_ = layout.slots;
  out_columns_ = layout.selected;
  selected_ = layout.selected_columns;
  units_row_ = layout.units_row;
}

void DelimitedParser::feed(std::string_view text) {
  const bool first_piece = bytes_fed_ == 0;
  piece_offset_ = bytes_fed_;
  bytes_fed_ += text.size();
  if (first_piece && text.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
    text.remove_prefix(kUtf8Bom.size());
    piece_offset_ += kUtf8Bom.size();
  }
  check_is_text(text, first_piece);
  any_text_ = any_text_ || !text.empty();
  text_ = text;
  pos_ = 0;
  Line line;
  while (next_line(&line)) parse_line(line);
  decide_index_column();
}

// Row numbers 0, 1, 2, ... in the first column, under a header without pandas' and R's mark of
// an index: fitting them as data is never what was meant, and dropping them unasked could drop
// real data, so the user says which (decided on the first piece of text: the whole file for
// read_table, the first block when streaming; kIndexDecisionRows rows at least).

void DelimitedParser::decide_index_column() {
  if (index_decided_ || rows_ < kIndexDecisionRows) return;
  index_decided_ = true;
  if (options_.index_column != IndexColumn::Auto || drop_first_ || columns_ < 2 || !first_column_counts_rows_) {
    return;
  }
  throw DataError(source_, first_data_line_, 1,
                  "the first column is 0, 1, 2, ...: row numbers (an index, as pandas' to_csv writes one), not "
                  "data? Drop it with --index-col (Python: index_col=True), or read it as data with "
                  "--no-index-col (index_col=False)");
}

namespace {

// A spreadsheet's error value (Excel's #N/A, #VALUE!, ...) as a line's first field: a line that
// begins so is a row with an error in its first cell, not a comment, so it is refused rather than
// skipped (skipping would shift every later row's number). The value, or empty.
std::string_view spreadsheet_error(std::string_view content) {
  static constexpr std::string_view kErrors[] = {"#N/A",   "#VALUE!", "#DIV/0!", "#REF!", "#NAME?",
                                                 "#NUM!",  "#NULL!",  "#SPILL!", "#CALC!"};
  for (std::string_view error : kErrors) {
    if (content.substr(0, error.size()) != error) continue;
    if (content.size() == error.size()) return error;
    const char next = content[error.size()];
    if (next == ',' || next == ';' || next == '\t' || next == ' ') return error;
  }
  return {};
}

// A line of commas and semicolons only (among blanks): a spreadsheet's empty row (Excel writes
// ",,,,," for a row it has formatted but holds no values, often many after the data), read as
// a blank line. (split_file.cpp's line scan decides so too.)
bool separators_only(std::string_view content) {
  return !content.empty() && content.find_first_not_of(",; \t") == std::string_view::npos;
}

}  // namespace

void DelimitedParser::parse_line(const Line& line) {
  if (!line.content.empty() && line.content[0] == '#') {
    const std::string_view error = spreadsheet_error(line.content);
    if (!error.empty()) {
      fail(line, 0,
           "'" + std::string(error) +
               "' is a spreadsheet's error value (a formula that failed), not a number; a line starting "
               "with # would otherwise be a comment, skipped, and every later row numbered one less: fix "
               "or delete that row in the spreadsheet, or export it again");
    }
  }
  if (line.content.empty() || line.content[0] == '#' || line.content[0] == '%') return;
  if (separators_only(line.content)) {
    if (rows_ > 0 || resumed_) {
      if (empty_rows_named_.size() + empty_rows_pending_lines_.size() < kNamedEmptyRows) {
        empty_rows_pending_lines_.push_back(line.number);
      }
      ++empty_rows_pending_;
    }
    return;
  }
  if (empty_rows_pending_ > 0) note_empty_rows();
  if (!seen_content_) {
    seen_content_ = true;
    separator_ = detect_separator(line.content);
    separator_line_ = line.number;
    const HeaderRow header = options_.header_row;
    if (header == HeaderRow::Absent) {
      // the first line is data
    } else {
      // pandas' to_csv and R's write.csv leave the index column's header cell empty; their
      // column names may be numbers (pandas' default names 0, 1, ...), and the line is still a header.
      const bool index_mark =
          options_.index_column == IndexColumn::Auto && !selecting() && header_first_cell_empty(line);
      // Without that mark, pandas' default names alone (to_csv(index=False) of a frame made from an
      // array) would be a row of data that no one measured.
      const bool pandas_names = header == HeaderRow::Auto && !index_mark && !is_header(line, separator_) &&
                                counts_columns(line);
      if (header == HeaderRow::Present || index_mark || pandas_names || is_header(line, separator_)) {
        keep_header(line);
        if (index_mark) {
          drop_first_ = true;
          warnings_.push_back(Warning(Code::FileNotice, source_ + kIndexColumnNotice +
                                      " (its header cell is empty, as pandas and R write an index): dropped; "
                                      "--no-index-col reads it as data (Python: index_col=False)"));
        }
        if (pandas_names) {
          warnings_.push_back(Warning(Code::FileNotice, source_ + ":" + std::to_string(line.number) + ": the first line, " +
                              abbreviated_count(line) +
                              ", is read as a header row (pandas' column names of a frame without names, as "
                              "to_csv(index=False) writes them), not as data; --no-header reads it as data "
                              "(Python: header=False)"));
        }
        return;
      }
      // Quoted numbers 1, 2, ..., k are data by the rule (every field reads as a number), but R's
      // write.csv writes the names of a matrix's numbered columns so: a decision worth saying.
      bool all_quoted = false;
      if (header == HeaderRow::Auto && counts_columns(line, 1, &all_quoted) && all_quoted) {
        warnings_.push_back(Warning(Code::FileNotice,
                                    source_ + ":" + std::to_string(line.number) + ": the first line, " +
                                        abbreviated_count(line, 1) +
                                        ", is read as data (every field is a number, quoted or not); if it names "
                                        "the columns (as R's write.csv quotes numbered names), the global "
                                        "option --header-row reads it as a header row (spdfit --header-row "
                                        "fit ...; Python: header=True)",
                                    source_));
      }
    }
  }
  const bool first_row = rows_ == 0 && !resumed_;
  if (have_header_ && first_row) choose_separator_after_header(line);
  if (have_header_ && first_row && !units_row_ && is_units_row(line)) {
    units_row_ = true;
    units_line_ = line.number;
    const std::string shown =
        line.content.size() <= 60 ? std::string(line.content) : std::string(line.content.substr(0, 57)) + "...";
    warnings_.push_back(Warning(Code::FileNotice,
                                source_ + ":" + std::to_string(line.number) + ": the line under the header, '" + shown +
                                    "', is read as a units row (as loggers write one under the column names) and "
                                    "skipped: none of its fields is a number",
                                source_));
    return;
  }
  if (first_row && selecting()) select_columns(line);

  const std::size_t fields = parse_row(line);
  if (first_row) first_data_line_ = line.number;
  if (!index_decided_ && !drop_first_ && fields > 0) {
    first_column_counts_rows_ =
        first_column_counts_rows_ && values_[values_.size() - fields] == static_cast<double>(rows_);
  }
  if (first_row) {
    columns_ = fields;
    columns_line_ = line.number;
    if (have_header_) {
      column_names_ = header_names(fields);
      columns_ = column_names_.size();
      columns_line_ = header_.number;
      if (selecting()) {
        std::vector<std::string> chosen;
        for (const auto& selection : selected_) {
          for (std::size_t c : selection) chosen.push_back(column_names_[c - 1]);
        }
        column_names_ = std::move(chosen);
      }
    }
  }
  if (fields != columns_) {
    fail(line, std::string_view::npos,
         "row has " + std::to_string(fields) + (fields == 1 ? " field" : " fields") + ", expected " +
             std::to_string(columns_) + " (as in line " + std::to_string(columns_line_) + ")");
  }
  ++rows_;
}

// Lines of separators only between data rows (empty_rows_pending_, now followed by a data row):
// one notice for the file, naming the first few such lines and counting them all, rewritten as
// more are found.
void DelimitedParser::note_empty_rows() {
  empty_rows_named_.insert(empty_rows_named_.end(), empty_rows_pending_lines_.begin(), empty_rows_pending_lines_.end());
  empty_rows_between_ += empty_rows_pending_;
  empty_rows_pending_lines_.clear();
  empty_rows_pending_ = 0;
  const std::size_t named = empty_rows_named_.size(), more = empty_rows_between_ - named;
  std::string lines;
  for (std::size_t k = 0; k < named; ++k) {
    const bool last = k + 1 == named && more == 0 && k > 0;
    lines += (k == 0 ? "" : last ? " and " : ", ") + std::to_string(empty_rows_named_[k]);
  }
  if (more > 0) lines += " and " + std::to_string(more) + " more";
  const bool one = empty_rows_between_ == 1;
  std::string text = source_ + ": " + (one ? "line " : "lines ") + lines + (one ? " holds" : " hold") +
                     " only separators (a spreadsheet's empty " + (one ? "row" : "rows") +
                     ") between data rows: skipped as blank lines are, so --rows numbers the data rows without " +
                     (one ? "it" : "them");
  if (empty_rows_notice_ == 0) {
    warnings_.push_back(Warning(Code::FileNotice, std::move(text), source_));
    empty_rows_notice_ = warnings_.size();
  } else {
    warnings_[empty_rows_notice_ - 1].text = std::move(text);
  }
}

// The header is needed again at the first data row, which may be in the next piece.
void DelimitedParser::keep_header(const Line& line) {
  have_header_ = true;
  header_raw_ = std::string(line.raw);
  const auto lead = static_cast<std::size_t>(line.content.data() - line.raw.data());
  header_.raw = header_raw_;
  header_.content = header_.raw.substr(lead, line.content.size());
  header_.number = line.number;
}

void DelimitedParser::finish() const {
  if (rows_ > 0 || resumed_) return;
  std::string problem = "no data rows";
  if (have_header_) {
    problem += " (only a header row, line " + std::to_string(header_.number) +
               (units_row_ ? ", and a units row, line " + std::to_string(units_line_) : std::string()) + ")";
  } else if (any_text_) {
    problem += " (only comments and blank lines)";
  } else {
    problem += " (the text is empty)";
  }
  throw DataError(source_, 0, 0, problem);
}

// Binary files (a spreadsheet's .xlsx, a MATLAB .mat) would otherwise produce a confusing
// "not a number" error somewhere in their first line; say what the file really is instead.
void DelimitedParser::check_is_text(std::string_view text, bool first_piece) const {
  if (first_piece && piece_offset_ == 0 &&
      (text.substr(0, 2) == "\xFF\xFE" || text.substr(0, 2) == "\xFE\xFF")) {
    throw DataError(source_, 0, 0,
                    "looks like UTF-16 text (such as Excel's \"Unicode Text\"); save it as "
                    "UTF-8 or plain CSV");
  }
  std::string description;
  const std::size_t offset = find_non_text_byte(text, &description);
  if (offset == std::string_view::npos) return;
  const TextPosition position = locate(text, offset);
  // The piece starts at a line start, after the lines of the earlier pieces.
  throw DataError(source_, line_number_ + position.line, position.column,
                  non_text_problem(text, offset, description, piece_offset_ + offset,
                                   first_piece && piece_offset_ == 0));
}

// Lines end at LF, CRLF, or a lone CR (the line end of old Mac spreadsheets).
bool DelimitedParser::next_line(Line* line) {
  if (pos_ >= text_.size()) return false;
  // A plain loop: string_view::find_first_of calls memchr once per byte.
  std::size_t end = pos_;
  while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
  line->raw = text_.substr(pos_, end - pos_);
  line->number = ++line_number_;
  pos_ = end + 1;
  if (end < text_.size() && text_[end] == '\r' && pos_ < text_.size() && text_[pos_] == '\n') {
    ++pos_;
  }
  line->content = trimmed(line->raw);
  return true;
}

bool DelimitedParser::next_field(const Line& line, FieldSplitter* splitter, Field* field) const {
  switch (splitter->next(field)) {
    case SplitStatus::Field:
      return true;
    case SplitStatus::End:
      return false;
    case SplitStatus::MissingClosingQuote:
      fail(line, field->offset, "missing closing quote");
    case SplitStatus::TextAfterClosingQuote:
      fail(line, field->offset, "unexpected text after closing quote");
  }
  return false;
}

// A header row is a first line with a name in it, a field that is not a number (and some field
// is not empty: a line of bare separators is an error, not a header), and no unquoted number. A
// quoted number reads as a number, as in data rows: a first row whose every field is a number,
// quoted or not (an export that quotes every cell), is data; beside names it may be one (R's
// write.csv quotes names such as "1"). NaN and Inf spellings count as numbers here, so that a
// first row of missing values is reported rather than taken as names.
bool DelimitedParser::is_header(const Line& line, Separator separator) const {
  FieldSplitter splitter(line.content, separator);
  Field field;
  bool any_name = false;
  while (next_field(line, &splitter, &field)) {
    if (field.quoted) {
      const std::string text = unquote(field);
      const std::string_view inside = trimmed(text);
      if (!inside.empty() && parse_number(inside).kind == NumberKind::NotANumber) any_name = true;
    } else if (!field.text.empty()) {
      if (parse_number(field.text).kind != NumberKind::NotANumber) return false;
      any_name = true;
    }
  }
  return any_name;
}

// "0,1,2,3" (start 0): two or more fields, exactly the integers start, start + 1, ... in order.
// `all_quoted`, when given, says whether every field was quoted.
bool DelimitedParser::counts_columns(const Line& line, std::size_t start, bool* all_quoted) const {
  if (separator_ == Separator::None) return false;
  FieldSplitter splitter(line.content, separator_);
  Field field;
  std::size_t count = 0;
  bool quoted = true;
  while (next_field(line, &splitter, &field)) {
    const std::string text = field.quoted ? unquote(field) : std::string(field.text);
    if (trimmed(text) != std::to_string(start + count)) return false;
    quoted = quoted && field.quoted;
    ++count;
  }
  if (all_quoted != nullptr) *all_quoted = quoted;
  return count >= 2;
}

// "0, 1, ..., 7" for a line counts_columns accepted from `start` (a wide frame's header in full
// would be long).
std::string DelimitedParser::abbreviated_count(const Line& line, std::size_t start) const {
  FieldSplitter splitter(line.content, separator_);
  Field field;
  std::size_t fields = 0;
  while (next_field(line, &splitter, &field)) ++fields;
  if (fields <= 4) return "'" + std::string(line.content) + "'";
  return std::to_string(start) + ", " + std::to_string(start + 1) + ", ..., " + std::to_string(start + fields - 1);
}

// ",Fx,Fy" or R's "","x1": two or more cells, the first empty (quoted or not), the others not.
bool DelimitedParser::header_first_cell_empty(const Line& line) const {
  if (separator_ == Separator::None || separator_ == Separator::Spaces) return false;  // runs of spaces: no empty cells
  FieldSplitter splitter(line.content, separator_);
  Field field;
  std::size_t count = 0;
  bool first_empty = false;
  while (next_field(line, &splitter, &field)) {
    if (count == 0) {
      first_empty = field.text.empty();
    } else if (field.text.empty()) {
      return false;  // ",,," is a line of separators, not a header
    }
    ++count;
  }
  return count >= 2 && first_empty;
}

// A line's fields, those that are text and those that are numbers (quoted or not, or with a decimal
// comma: "3,5"; NaN and Inf spellings count as numbers, as in is_header); empty fields are neither.
DelimitedParser::FieldKinds DelimitedParser::field_kinds(const Line& line) const {
  FieldSplitter splitter(line.content, separator_);
  Field field;
  FieldKinds kinds;
  while (next_field(line, &splitter, &field)) {
    std::string value(trimmed(field.quoted ? unquote(field) : std::string(field.text)));
    std::replace(value.begin(), value.end(), ',', '.');
    if (!value.empty()) ++(parse_number(value).kind == NumberKind::NotANumber ? kinds.text : kinds.numbers);
    ++kinds.fields;
  }
  return kinds;
}

// A units row under the header ("s,N,N,N*m"): as many fields as the header, some text, and no
// field a number, so that skipping it loses no value.
bool DelimitedParser::is_units_row(const Line& line) const {
  const FieldKinds kinds = field_kinds(line);
  if (kinds.text == 0 || kinds.numbers > 0) return false;
  FieldSplitter names(header_.content, separator_);
  Field field;
  std::size_t header_fields = 0;
  while (next_field(header_, &names, &field)) ++header_fields;
  return kinds.fields == header_fields;
}

// The header's own separator may be unknown (a single name, perhaps with spaces, as in
// "Force (N)") and the first data line may be a single number; otherwise the two must agree.
void DelimitedParser::choose_separator_after_header(const Line& data) {
  const Separator from_data = detect_separator(data.content);
  if (from_data == Separator::None || from_data == separator_) return;
  if (separator_ == Separator::None) {
    separator_ = from_data;
    separator_line_ = data.number;
    return;
  }
  fail(data, std::string_view::npos,
       "this line separates fields with " + separator_name(from_data) + ", but the header (line " +
           std::to_string(header_.number) + ") uses " + separator_name(separator_));
}

std::vector<std::string> DelimitedParser::header_names(std::size_t data_fields) const {
  const Line& header = header_;
  std::vector<std::string> names;
  FieldSplitter splitter(header.content, separator_);
  Field field;
  bool any_quoted = false;
  while (next_field(header, &splitter, &field)) {
    names.push_back(unquote(field));
    any_quoted |= field.quoted;
  }
  if (drop_first_ && !names.empty()) names.erase(names.begin());
  // A single column of numbers under a header with spaces ("Force (N)"): the spaces belong to
  // the name, since there are no other columns for them to separate.
  const bool by_spaces = separator_ == Separator::Spaces || separator_ == Separator::None;
  if (by_spaces && data_fields == 1 && !any_quoted && names.size() > 1) {
    names.assign(1, std::string(header.content));
  }
  return names;
}

// The selections resolved on the header and the first data row's fields: which fields a row's
// values come from, in order.
void DelimitedParser::select_columns(const Line& first_row) {
  FieldSplitter splitter(first_row.content, separator_);
  Field field;
  std::size_t fields = 0;
  while (next_field(first_row, &splitter, &field)) ++fields;
  if (drop_first_ && fields > 0) --fields;
  const std::vector<std::string> names = have_header_ ? header_names(fields) : std::vector<std::string>{};
  const std::size_t columns = have_header_ ? names.size() : fields;
  const auto chosen = resolve_columns(options_.columns, names, columns, true, source_);
  slots_.assign(std::max(columns, fields), -1);
  long slot = 0;
  for (std::size_t c : concatenated(chosen)) slots_[c] = slot++;
  out_columns_ = static_cast<std::size_t>(slot);
  selected_ = one_based(chosen);
}

namespace {
// "2024-01-31", "10:15:02.5", "2024-01-31T10:15:02Z", "31/01/2024": a date or time of day, as a
// log's first column holds one.
bool looks_like_timestamp(std::string_view t) {
  if (t.empty() || !std::isdigit(static_cast<unsigned char>(t[0]))) return false;
  bool mark = false;
  for (char c : t) {
    if (c == '-' || c == ':' || c == '/') {
      mark = true;
    } else if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.' && c != 'T' && c != 'Z' && c != '+' &&
               c != ' ') {
      return false;
    }
  }
  return mark;
}

constexpr const char* kTimestampHint =
    "; a timestamp in the first column? --index-col drops it (Python: index_col=True), or --a-cols "
    "and --b-cols choose the columns of A and B (Python: a_cols, b_cols)";
}  // namespace

std::size_t DelimitedParser::parse_row(const Line& line) {
  FieldSplitter splitter(line.content, separator_);
  Field field;
  std::size_t count = 0;
  bool label = drop_first_;  // the row's label: skipped, whatever it says
  const bool selecting = this->selecting();
  const std::size_t base = values_.size();
  if (selecting) values_.resize(base + out_columns_);
  while (next_field(line, &splitter, &field)) {
    if (label) {
      label = false;
      if (keep_row_labels_) row_names_.push_back(field.quoted ? unquote(field) : std::string(field.text));
      continue;
    }
    long slot = -1;
    if (selecting) {
      slot = count < slots_.size() ? slots_[count] : -1;
      current_column_ = count;
      if (slot < 0) {  // not selected: not parsed, whatever it holds
        ++count;
        continue;
      }
    }
    // A quoted number in a data row ("1.5", as some spreadsheets and exporters write every cell)
    // reads as the number, spaces around it allowed as around unquoted fields; quoted text is still
    // not one. (In the first line quoted tokens count as names: R's header "","1","2" stays a
    // header; see is_header.)
    std::string unquoted;
    Field value = field;
    if (field.quoted) {
      unquoted = unquote(field);
      value.text = trimmed(unquoted);
      if (!value.text.empty() && parse_number(value.text).kind == NumberKind::NotANumber) {
        const std::string_view quoted = line.content.substr(field.offset, field.text.size() + 2);
        std::string problem = quote_token(quoted) + " is quoted text, not a number" + selected_column_note();
        if (!selecting && field.offset <= 1 && looks_like_timestamp(value.text)) problem += kTimestampHint;
        if (value.text.find(',') != std::string_view::npos && separator_ != Separator::Comma) {
          problem += " (decimal comma? use '.' for decimals)";
        }
        fail(line, field.offset, problem);
      }
    }
    // An empty field is pandas' NaN: read as one where NaN is allowed, an error otherwise.
    if (value.text.empty() && !options_.allow_nonfinite) fail_empty_field(line, field, count);
    const double parsed = value.text.empty() ? std::numeric_limits<double>::quiet_NaN() : parse_value(line, value);
    if (selecting) {
      values_[base + static_cast<std::size_t>(slot)] = parsed;
    } else {
      values_.push_back(parsed);
    }
    ++count;
  }
  return count;
}

double DelimitedParser::parse_value(const Line& line, const Field& field) const {
  const ParsedNumber number = parse_number(field.text);
  const bool negative = number.value < 0;
  switch (number.kind) {
    case NumberKind::Finite:
      return number.value;
    case NumberKind::NaN:
      if (!options_.allow_nonfinite) fail(line, field.offset, "NaN is not allowed" + selected_column_note());
      return number.value;
    case NumberKind::Infinity:
      if (!options_.allow_nonfinite) {
        fail(line, field.offset, negative ? "-Inf is not allowed" : "Inf is not allowed");
      }
      return number.value;
    case NumberKind::Overflow:
      if (!options_.allow_nonfinite) {
        fail(line, field.offset,
             quote_token(field.text) + " is too large for a double (it would be " +
                 (negative ? "-Inf)" : "Inf)"));
      }
      return number.value;
    case NumberKind::NotANumber:
      break;
  }
  fail_not_a_number(line, field);
}

void DelimitedParser::fail_empty_field(const Line& line, const Field& field, std::size_t index) const {
  const bool tab = separator_ == Separator::Tab;
  const std::string one = tab ? "a tab" : separator_name(separator_);
  // pandas' to_csv writes a missing value (NaN) as nothing at all, the usual source of these.
  const std::string hint = "; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)";
  if (field.offset >= line.content.size()) {
    fail(line, line.content.size() - 1, "empty field: the line ends with " + one + hint);
  }
  if (index == 0) fail(line, field.offset, "empty field: the line starts with " + one + hint);
  fail(line, field.offset, "empty field: nothing between two " + separator_name(separator_) + hint);
}

// Says why a field is not a number, pointing at a separator the file does not use when there
// is one, because a mixed-up separator is the usual cause.
void DelimitedParser::fail_not_a_number(const Line& line, const Field& field) const {
  const std::string_view t = field.text;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const char c = t[k];
    const bool foreign =
        (c == ';' && separator_ != Separator::Semicolon) ||
        (c == ',' && separator_ != Separator::Comma && separator_ != Separator::Semicolon) ||
        (c == '\t' && separator_ != Separator::Tab);
    if (foreign) {
      const std::string found = c == '\t' ? "a tab" : std::string("'") + c + "'";
      fail(line, field.offset + k, "found " + found + " here, but " + separator_origin());
    }
  }
  std::string problem = quote_token(t) + " is not a number";
  if (have_header_ && rows_ == 0 && !resumed_ && !units_row_) {
    // Directly under the header, mostly text: a units row with a number in it ("1" for a
    // dimensionless column)?
    const FieldKinds kinds = field_kinds(line);
    if (2 * kinds.text > kinds.fields) {
      problem += "; a units row under the header? It is skipped only when none of its fields is a number";
    }
  }
  const bool decimal_comma = separator_ == Separator::Semicolon && t.find(',') != std::string_view::npos;
  if (selecting()) {
    problem += selected_column_note();
    if (decimal_comma) problem += " (decimal comma? use '.' for decimals)";
  } else if (field.offset <= 1 && looks_like_timestamp(t)) {
    problem += kTimestampHint;
  } else if (decimal_comma) {
    problem += " (decimal comma? use '.' for decimals)";
  } else if (t.find(' ') != std::string_view::npos) {
    problem += "; " + separator_origin();
  }
  fail(line, field.offset, problem);
}

std::string DelimitedParser::selected_column_note() const {
  std::string note;
  if (!selecting()) return note;
  for (std::size_t k = 0; k < selected_.size(); ++k) {
    for (std::size_t c : selected_[k]) {
      if (c == current_column_ + 1) {
        note += "; column " + std::to_string(c) + " is selected by `" + options_.columns[k].option + "` '" +
                options_.columns[k].spec + "'";
      }
    }
  }
  return note;
}

std::string DelimitedParser::separator_origin() const {
  if (separator_ == Separator::None) {
    return "line " + std::to_string(separator_line_) + " has a single field";
  }
  return "fields in this file are separated by " + separator_name(separator_) + " (see line " +
         std::to_string(separator_line_) + ")";
}

// `offset` is into line.content; npos means the whole line (no column). Columns are counted
// only here, on failure, so that long lines cost nothing extra.
void DelimitedParser::fail(const Line& line, std::size_t offset, const std::string& problem) const {
  std::size_t column = 0;
  if (offset != std::string_view::npos) {
    const auto lead = static_cast<std::size_t>(line.content.data() - line.raw.data());
    column = column_after(line.raw.substr(0, lead + offset));
  }
  throw DataError(source_, line.number, column, problem);
}

}  // namespace detail

Table detail::parse_delimited_labelled(std::string_view text, const std::string& source, const ReadOptions& options,
                                       std::vector<std::string>* row_names) {
  detail::DelimitedParser parser(source, options);
  if (row_names != nullptr) parser.keep_row_labels();
  parser.feed(text);
  parser.finish();
  Table table;
  table.column_names = parser.column_names();
  table.warnings = parser.warnings();
  table.first_data_line = parser.first_data_line();
  table.selected_columns = parser.selected_columns();
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  table.values = Eigen::Map<const RowMajor>(parser.values().data(), static_cast<Eigen::Index>(parser.rows()),
                                            static_cast<Eigen::Index>(parser.columns()));
  if (row_names != nullptr) *row_names = parser.row_names();
  return table;
}

Table parse_delimited(std::string_view text, const std::string& source, const ReadOptions& options) {
  return detail::parse_delimited_labelled(text, source, options, nullptr);
}

}  // namespace spdfit::io
