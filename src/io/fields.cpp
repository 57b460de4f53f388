#include "fields.hpp"

namespace spdfit::io::detail {

namespace {

// The quote that closes the one at `open` ("" inside is an escaped quote), or npos.
std::size_t find_closing_quote(std::string_view s, std::size_t open) {
  std::size_t i = open + 1;
  while (true) {
    const std::size_t quote = s.find('"', i);
    if (quote == std::string_view::npos) return quote;
    if (quote + 1 < s.size() && s[quote + 1] == '"') {
      i = quote + 2;
      continue;
    }
    return quote;
  }
}

}  // namespace

std::string separator_name(Separator separator) {
  switch (separator) {
    case Separator::Semicolon:
      return "';'";
    case Separator::Comma:
      return "','";
    case Separator::Tab:
      return "tabs";
    case Separator::Spaces:
    case Separator::None:
      break;
  }
  return "spaces";
}

Separator detect_separator(std::string_view content) {
  bool in_quotes = false;
  bool semicolon = false, comma = false, tab = false, space = false;
  for (const char c : content) {
    if (c == '"') {
      in_quotes = !in_quotes;
    } else if (!in_quotes) {
      semicolon |= c == ';';
      comma |= c == ',';
      tab |= c == '\t';
      space |= c == ' ';
    }
  }
  if (semicolon) return Separator::Semicolon;
  if (comma) return Separator::Comma;
  if (tab) return Separator::Tab;
  if (space) return Separator::Spaces;
  return Separator::None;
}

std::string unquote(const Field& field) {
  if (!field.quoted) return std::string(field.text);
  std::string text;
  text.reserve(field.text.size());
  for (std::size_t i = 0; i < field.text.size(); ++i) {
    text += field.text[i];
    if (field.text[i] == '"') ++i;  // skip the second quote of ""
  }
  return text;
}

FieldSplitter::FieldSplitter(std::string_view content, Separator separator)
    : content_(content), separator_(separator), done_(content.empty()) {}

SplitStatus FieldSplitter::next(Field* field) {
  if (done_) return SplitStatus::End;
  if (separator_ == Separator::Spaces || separator_ == Separator::None) {
    return next_space_separated(field);
  }
  const std::string_view s = content_;
  const std::size_t n = s.size();
  const char separator = separator_ == Separator::Semicolon ? ';'
                         : separator_ == Separator::Comma   ? ','
                                                             : '\t';
  // Blanks around a separator are padding ("1, 2, 3"); a tab is padding unless it separates.
  const auto is_padding = [separator](char c) { return c == ' ' || (c == '\t' && separator != '\t'); };
  std::size_t i = pos_;
  while (i < n && is_padding(s[i])) ++i;
  std::size_t end = 0;
  if (i < n && s[i] == '"') {
    const std::size_t close = find_closing_quote(s, i);
    if (close == std::string_view::npos) {
      field->offset = i;
      return SplitStatus::MissingClosingQuote;
    }
    *field = {s.substr(i + 1, close - i - 1), i, true};
    end = close + 1;
    while (end < n && is_padding(s[end])) ++end;
    if (end < n && s[end] != separator) {
      field->offset = end;
      return SplitStatus::TextAfterClosingQuote;
    }
  } else {
    end = s.find(separator, i);
    if (end == std::string_view::npos) end = n;
    std::size_t last = end;
    while (last > i && is_padding(s[last - 1])) --last;
    *field = {s.substr(i, last - i), i, false};
  }
  if (end >= n) {
    done_ = true;
  } else {
    pos_ = end + 1;  // a separator at the very end leaves one more, empty, field
  }
  return SplitStatus::Field;
}

SplitStatus FieldSplitter::next_space_separated(Field* field) {
  // The line has no leading or trailing blanks and runs of spaces are skipped below, so pos_
  // is at the first character of a field.
  const std::string_view s = content_;
  const std::size_t n = s.size();
  const std::size_t i = pos_;
  std::size_t end = 0;
  if (s[i] == '"') {
    const std::size_t close = find_closing_quote(s, i);
    if (close == std::string_view::npos) {
      field->offset = i;
      return SplitStatus::MissingClosingQuote;
    }
    *field = {s.substr(i + 1, close - i - 1), i, true};
    end = close + 1;
    if (end < n && s[end] != ' ') {
      field->offset = end;
      return SplitStatus::TextAfterClosingQuote;
    }
  } else {
    end = s.find(' ', i);
    if (end == std::string_view::npos) end = n;
    *field = {s.substr(i, end - i), i, false};
  }
  while (end < n && s[end] == ' ') ++end;
  pos_ = end;
  done_ = end >= n;
  return SplitStatus::Field;
}

}  // namespace spdfit::io::detail
