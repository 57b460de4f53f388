// Splitting one line of delimited text into fields: the separator a line uses, and quoting.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace spdfit::io::detail {

/// What separates the fields of a line. kNone: the line holds a single field, so it does not
/// tell; it is split like kSpaces.
enum class Separator { None, Semicolon, Comma, Tab, Spaces };

/// The separator as a plural noun for messages: "';'", "','", "tabs", "spaces".
std::string separator_name(Separator separator);

/// The separator of a line: semicolon if it has one, else comma, else tab, else a space, else
/// kNone. Characters inside double quotes do not count, so that a header name like "x, mm" does
/// not make a tab-separated file look comma-separated. `content` has no leading or trailing
/// blanks.
Separator detect_separator(std::string_view content);

/// One field of a line. For a quoted field, `text` is what is between the quotes ("" not yet
/// undone: see unquote).
struct Field {
  std::string_view text;
  std::size_t offset = 0;  ///< in the line's content: the first character or the opening quote
  bool quoted = false;
};

/// The text of a field with the quoting undone.
std::string unquote(const Field& field);

enum class SplitStatus { Field, End, MissingClosingQuote, TextAfterClosingQuote };

/// Splits a line (without leading or trailing blanks) into fields, one per next() call, without
/// parsing them. With kComma, kSemicolon and kTab, blanks around a separator are padding and
/// two separators in a row make an empty field; with kSpaces and kNone a run of spaces is one
/// separator. A field that starts with '"' runs to the closing quote, separators included.
class FieldSplitter {
 public:
  FieldSplitter(std::string_view content, Separator separator);

  /// kField with the next field; kEnd after the last one; on bad quoting, field->offset is the
  /// offending position.
  SplitStatus next(Field* field);

 private:
  SplitStatus next_space_separated(Field* field);

  std::string_view content_;
  Separator separator_;
  std::size_t pos_ = 0;
  bool done_ = false;
};

}  // namespace spdfit::io::detail
