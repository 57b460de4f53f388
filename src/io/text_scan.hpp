// Byte- and token-level helpers for the delimited-text reader: text validation, positions for
// error messages, and number tokens.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace spdfit::io::detail {

/// The first byte at which `text` stops looking like text: NUL, a control character other than
/// tab, CR and LF, or a byte that is not valid UTF-8. Returns std::string_view::npos when there
/// is none; otherwise `description` says what was found (e.g. "NUL byte").
std::size_t find_non_text_byte(std::string_view text, std::string* description);

/// What text that find_non_text_byte stopped at `offset` most likely is, as an error message
/// that says what to do: UTF-16 without a byte-order mark, or text in a Windows code page
/// (Windows-1252 / Latin-1, as Excel's plain "CSV" saves: the byte shown as that character)
/// say "save it as UTF-8"; anything else "looks like a binary file, not text (`description`
/// at byte offset `file_offset`)", naming a ZIP archive (.xlsx) or an old .xls workbook by their
/// signatures when `at_start` (text begins at the file's first byte).
std::string non_text_problem(std::string_view text, std::size_t offset, const std::string& description,
                             std::size_t file_offset, bool at_start);

/// A 1-based line and character column.
struct TextPosition {
  std::size_t line;
  std::size_t column;
};

/// Where byte `offset` of `text` is. Lines end at LF, CRLF or a lone CR, as in the reader;
/// columns count UTF-8 characters, not bytes.
TextPosition locate(std::string_view text, std::size_t offset);

/// The 1-based character column of the byte just after `line_prefix` (valid UTF-8).
std::size_t column_after(std::string_view line_prefix);

/// What a field of delimited text holds.
enum class NumberKind {
  Finite,      ///< a finite number (values that underflow read as denormals or signed zero)
  NaN,         ///< spelled NaN (any case, optionally signed or with a payload "nan(...)")
  Infinity,    ///< spelled inf or infinity (any case, optionally signed)
  Overflow,    ///< a finite spelling too large for a double, e.g. 1e999; value is +-Inf
  NotANumber,  ///< anything else, including text after a number ("1.5abc") and "1e"
};

struct ParsedNumber {
  NumberKind kind;
  double value;
};

/// Parses a whole field as a double with std::from_chars, also accepting a leading '+'.
ParsedNumber parse_number(std::string_view token);

/// `token` in single quotes for an error message, shortened (at a character boundary) when
/// it is long so that a hostile multi-megabyte field does not become a multi-megabyte message.
std::string quote_token(std::string_view token);

}  // namespace spdfit::io::detail
