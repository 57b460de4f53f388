// The delimited-text reader: CSV, semicolon-separated (European spreadsheets), tab-separated,
// and space-aligned columns (MATLAB's save -ascii).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "fields.hpp"
#include "spdfit/io.hpp"
#include "text_scan.hpp"

namespace spdfit::io {

namespace {

using detail::detect_separator;
using detail::Field;
using detail::FieldSplitter;
using detail::NumberKind;
using detail::quote_token;
using detail::Separator;
using detail::separator_name;
using detail::SplitStatus;

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// One line of the text, without its line end.
struct Line {
  std::string_view raw;
  std::string_view content;  // raw without leading and trailing blanks
  std::size_t number = 0;    // 1-based
};

class DelimitedParser {
 public:
  DelimitedParser(std::string_view text, const std::string& source, const ReadOptions& options)
      : text_(text), source_(source), options_(options) {}

  Table parse();

 private:
  void check_is_text() const;
  bool next_line(Line* line);
  bool next_field(const Line& line, FieldSplitter* splitter, Field* field) const;
  bool is_header(const Line& line, Separator separator) const;
  void choose_separator_after_header(const Line& header, const Line& data);
  std::vector<std::string> column_names(const Line& header, std::size_t data_fields) const;
  std::size_t parse_row(const Line& line);
  double parse_value(const Line& line, const Field& field) const;
  [[noreturn]] void fail_empty_field(const Line& line, const Field& field, std::size_t index) const;
  [[noreturn]] void fail_not_a_number(const Line& line, const Field& field) const;
  std::string separator_origin() const;
  [[noreturn]] void fail(const Line& line, std::size_t offset, const std::string& problem) const;

  std::string_view text_;  // after the byte-order mark
  std::size_t bom_size_ = 0;
  const std::string& source_;
  const ReadOptions& options_;

  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;

  Separator separator_ = Separator::kNone;
  std::size_t separator_line_ = 0;  // the line that decided separator_
  std::vector<double> values_;      // row-major; at most one per two bytes of text
};

Table DelimitedParser::parse() {
  if (text_.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
    text_.remove_prefix(kUtf8Bom.size());
    bom_size_ = kUtf8Bom.size();
  }
  check_is_text();

  Table table;
  Line line;
  Line header;
  bool have_header = false;
  bool seen_content = false;
  std::size_t rows = 0;
  std::size_t columns = 0;
  std::size_t columns_line = 0;
  while (next_line(&line)) {
    if (line.content.empty() || line.content[0] == '#' || line.content[0] == '%') continue;
    if (!seen_content) {
      seen_content = true;
      separator_ = detect_separator(line.content);
      separator_line_ = line.number;
      if (is_header(line, separator_)) {
        header = line;
        have_header = true;
        continue;
      }
    }
    if (have_header && rows == 0) choose_separator_after_header(header, line);

    const std::size_t fields = parse_row(line);
    if (rows == 0) {
      columns = fields;
      columns_line = line.number;
      if (have_header) {
        table.column_names = column_names(header, fields);
        columns = table.column_names.size();
        columns_line = header.number;
      }
    }
    if (fields != columns) {
      fail(line, std::string_view::npos,
           "row has " + std::to_string(fields) + (fields == 1 ? " field" : " fields") + ", expected " +
               std::to_string(columns) + " (as in line " + std::to_string(columns_line) + ")");
    }
    ++rows;
  }

  if (rows == 0) {
    std::string problem = "no data rows";
    if (have_header) {
      problem += " (only a header row, line " + std::to_string(header.number) + ")";
    } else if (!text_.empty()) {
      problem += " (only comments and blank lines)";
    } else {
      problem += " (the text is empty)";
    }
    throw DataError(source_, 0, 0, problem);
  }
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  table.values = Eigen::Map<const RowMajor>(values_.data(), static_cast<Eigen::Index>(rows),
                                            static_cast<Eigen::Index>(columns));
  return table;
}

// Binary files (a spreadsheet's .xlsx, a MATLAB .mat) would otherwise produce a confusing
// "not a number" error somewhere in their first line; say what the file really is instead.
void DelimitedParser::check_is_text() const {
  if (bom_size_ == 0 && (text_.substr(0, 2) == "\xFF\xFE" || text_.substr(0, 2) == "\xFE\xFF")) {
    throw DataError(source_, 0, 0,
                    "looks like UTF-16 text (such as Excel's \"Unicode Text\"); save it as "
                    "UTF-8 or plain CSV");
  }
  std::string description;
  const std::size_t offset = detail::find_non_text_byte(text_, &description);
  if (offset == std::string_view::npos) return;
  const detail::TextPosition position = detail::locate(text_, offset);
  throw DataError(source_, position.line, position.column,
                  "looks like a binary file, not text (" + description + " at byte offset " +
                      std::to_string(offset + bom_size_) + ")");
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
  std::size_t first = 0;
  std::size_t last = line->raw.size();
  while (first < last && is_blank(line->raw[first])) ++first;
  while (last > first && is_blank(line->raw[last - 1])) --last;
  line->content = line->raw.substr(first, last - first);
  return true;
}

bool DelimitedParser::next_field(const Line& line, FieldSplitter* splitter, Field* field) const {
  switch (splitter->next(field)) {
    case SplitStatus::kField:
      return true;
    case SplitStatus::kEnd:
      return false;
    case SplitStatus::kMissingClosingQuote:
      fail(line, field->offset, "missing closing quote");
    case SplitStatus::kTextAfterClosingQuote:
      fail(line, field->offset, "unexpected text after closing quote");
  }
  return false;
}

// A header row is a first line in which no field is a number (and some field is not empty:
// a line of bare separators is an error, not a header). NaN and Inf spellings count as numbers
// here, so that a first row of missing values is reported rather than taken as names.
bool DelimitedParser::is_header(const Line& line, Separator separator) const {
  FieldSplitter splitter(line.content, separator);
  Field field;
  bool any_name = false;
  while (next_field(line, &splitter, &field)) {
    if (field.quoted) {
      any_name = true;
    } else if (!field.text.empty()) {
      if (detail::parse_number(field.text).kind != NumberKind::kNotANumber) return false;
      any_name = true;
    }
  }
  return any_name;
}

// The header's own separator may be unknown (a single name, perhaps with spaces, as in
// "Force (N)") and the first data line may be a single number; otherwise the two must agree.
void DelimitedParser::choose_separator_after_header(const Line& header, const Line& data) {
  const Separator from_data = detect_separator(data.content);
  if (from_data == Separator::kNone || from_data == separator_) return;
  if (separator_ == Separator::kNone) {
    separator_ = from_data;
    separator_line_ = data.number;
    return;
  }
  fail(data, std::string_view::npos,
       "this line separates fields with " + separator_name(from_data) + ", but the header (line " +
           std::to_string(header.number) + ") uses " + separator_name(separator_));
}

std::vector<std::string> DelimitedParser::column_names(const Line& header, std::size_t data_fields) const {
  std::vector<std::string> names;
  FieldSplitter splitter(header.content, separator_);
  Field field;
  bool any_quoted = false;
  while (next_field(header, &splitter, &field)) {
    names.push_back(detail::unquote(field));
    any_quoted |= field.quoted;
  }
  // A single column of numbers under a header with spaces ("Force (N)"): the spaces belong to
  // the name, since there are no other columns for them to separate.
  const bool by_spaces = separator_ == Separator::kSpaces || separator_ == Separator::kNone;
  if (by_spaces && data_fields == 1 && !any_quoted && names.size() > 1) {
    names.assign(1, std::string(header.content));
  }
  return names;
}

std::size_t DelimitedParser::parse_row(const Line& line) {
  FieldSplitter splitter(line.content, separator_);
  Field field;
  std::size_t count = 0;
  while (next_field(line, &splitter, &field)) {
    if (field.quoted) {
      const std::string_view quoted = line.content.substr(field.offset, field.text.size() + 2);
      fail(line, field.offset, quote_token(quoted) + " is quoted text, not a number");
    }
    if (field.text.empty()) fail_empty_field(line, field, count);
    values_.push_back(parse_value(line, field));
    ++count;
  }
  return count;
}

double DelimitedParser::parse_value(const Line& line, const Field& field) const {
  const detail::ParsedNumber number = detail::parse_number(field.text);
  const bool negative = number.value < 0;
  switch (number.kind) {
    case NumberKind::kFinite:
      return number.value;
    case NumberKind::kNaN:
      if (!options_.allow_nonfinite) fail(line, field.offset, "NaN is not allowed");
      return number.value;
    case NumberKind::kInfinity:
      if (!options_.allow_nonfinite) {
        fail(line, field.offset, negative ? "-Inf is not allowed" : "Inf is not allowed");
      }
      return number.value;
    case NumberKind::kOverflow:
      if (!options_.allow_nonfinite) {
        fail(line, field.offset,
             quote_token(field.text) + " is too large for a double (it would be " +
                 (negative ? "-Inf)" : "Inf)"));
      }
      return number.value;
    case NumberKind::kNotANumber:
      break;
  }
  fail_not_a_number(line, field);
}

void DelimitedParser::fail_empty_field(const Line& line, const Field& field, std::size_t index) const {
  const bool tab = separator_ == Separator::kTab;
  const std::string one = tab ? "a tab" : separator_name(separator_);
  if (field.offset >= line.content.size()) {
    fail(line, line.content.size() - 1, "empty field: the line ends with " + one);
  }
  if (index == 0) fail(line, field.offset, "empty field: the line starts with " + one);
  fail(line, field.offset, "empty field: nothing between two " + separator_name(separator_));
}

// Says why a field is not a number, pointing at a separator the file does not use when there
// is one, because a mixed-up separator is the usual cause.
void DelimitedParser::fail_not_a_number(const Line& line, const Field& field) const {
  const std::string_view t = field.text;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const char c = t[k];
    const bool foreign =
        (c == ';' && separator_ != Separator::kSemicolon) ||
        (c == ',' && separator_ != Separator::kComma && separator_ != Separator::kSemicolon) ||
        (c == '\t' && separator_ != Separator::kTab);
    if (foreign) {
      const std::string found = c == '\t' ? "a tab" : std::string("'") + c + "'";
      fail(line, field.offset + k, "found " + found + " here, but " + separator_origin());
    }
  }
  std::string problem = quote_token(t) + " is not a number";
  if (separator_ == Separator::kSemicolon && t.find(',') != std::string_view::npos) {
    problem += " (decimal comma? use '.' for decimals)";
  } else if (t.find(' ') != std::string_view::npos) {
    problem += "; " + separator_origin();
  }
  fail(line, field.offset, problem);
}

std::string DelimitedParser::separator_origin() const {
  if (separator_ == Separator::kNone) {
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
    column = detail::column_after(line.raw.substr(0, lead + offset));
  }
  throw DataError(source_, line.number, column, problem);
}

}  // namespace

Table parse_delimited(std::string_view text, const std::string& source, const ReadOptions& options) {
  return DelimitedParser(text, source, options).parse();
}

}  // namespace spdfit::io
