#include "text_scan.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <system_error>

namespace spdfit::io::detail {

namespace {

bool is_continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

std::string hex_byte(unsigned char c) {
  char buffer[8];
  std::snprintf(buffer, sizeof(buffer), "0x%02X", static_cast<unsigned>(c));
  return buffer;
}

// Length of the valid UTF-8 sequence starting at p[i], or 0 if it is not one. Follows RFC 3629
// (Table 3-7 of the Unicode standard): no overlong forms, no surrogates, nothing past U+10FFFF.
std::size_t utf8_sequence_length(const unsigned char* p, std::size_t n, std::size_t i) {
  const unsigned char c = p[i];
  std::size_t length = 0;
  unsigned char low = 0x80;
  unsigned char high = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    length = 2;
  } else if (c == 0xE0) {
    length = 3;
    low = 0xA0;
  } else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) {
    length = 3;
  } else if (c == 0xED) {
    length = 3;
    high = 0x9F;
  } else if (c == 0xF0) {
    length = 4;
    low = 0x90;
  } else if (c >= 0xF1 && c <= 0xF3) {
    length = 4;
  } else if (c == 0xF4) {
    length = 4;
    high = 0x8F;
  } else {
    return 0;
  }
  if (n - i < length) return 0;
  if (p[i + 1] < low || p[i + 1] > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (!is_continuation(p[i + k])) return 0;
  }
  return length;
}

// Decides whether a token that from_chars matched but reported out of range is too large or
// too small. from_chars leaves the value unset in both cases, so this looks at the decimal
// exponent of the leading significant digit. Anything out of range has that exponent >= 308
// or <= -324, so its sign is enough. `token` is a complete decimal float without a '+'.
bool is_overflow(std::string_view token) {
  std::size_t i = 0;
  if (i < token.size() && token[i] == '-') ++i;
  // Exponent of the first nonzero digit relative to the decimal point, before the 'e' part.
  long long magnitude = 0;
  bool found = false;
  long long integer_digits = 0;
  for (; i < token.size() && token[i] >= '0' && token[i] <= '9'; ++i) {
    if (found) {
      ++integer_digits;
    } else if (token[i] != '0') {
      found = true;
      integer_digits = 1;
    }
  }
  if (found) magnitude = integer_digits - 1;
  if (i < token.size() && token[i] == '.') {
    ++i;
    long long position = 0;
    for (; i < token.size() && token[i] >= '0' && token[i] <= '9'; ++i) {
      ++position;
      if (!found && token[i] != '0') {
        found = true;
        magnitude = -position;
      }
    }
  }
  long long exponent = 0;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    bool negative = false;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) negative = token[i++] == '-';
    // Saturate: the exact value of an absurd exponent does not matter, only its sign.
    constexpr long long kCap = 1'000'000'000'000LL;
    for (; i < token.size() && token[i] >= '0' && token[i] <= '9'; ++i) {
      if (exponent < kCap) exponent = exponent * 10 + (token[i] - '0');
    }
    if (negative) exponent = -exponent;
  }
  return magnitude + exponent > 0;
}

// Windows-1252's characters for the bytes 0x80-0x9F (0 where it defines none); from 0xA0 on it
// is Latin-1, whose byte b is the code point U+00b.
constexpr char32_t kCp1252High[32] = {
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0,      0x017D, 0,      0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178};

std::string utf8_of(char32_t c) {
  std::string out;
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
  return out;
}

// Whether `text` (a window of a file) holds no control character but tab, CR and LF, and no
// NUL: text, whatever its encoding.
bool no_control_characters(std::string_view text) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F) return false;
  }
  return true;
}

// Whether `text` looks like UTF-16 without a byte-order mark: in its first bytes every other
// byte is NUL and the others are printable ASCII or line ends (the digits, separators and names
// of a data file).
bool looks_like_utf16(std::string_view text) {
  const std::size_t n = std::min<std::size_t>(text.size(), 256) & ~std::size_t{1};
  if (n < 4) return false;
  for (std::size_t zero_at : {std::size_t{0}, std::size_t{1}}) {
    bool all = true;
    for (std::size_t i = 0; i < n && all; ++i) {
      const auto c = static_cast<unsigned char>(text[i]);
      all = (i % 2 == zero_at) ? c == 0 : (c >= 0x20 && c < 0x7F) || c == '\t' || c == '\n' || c == '\r';
    }
    if (all) return true;
  }
  return false;
}

}  // namespace

std::string non_text_problem(std::string_view text, std::size_t offset, const std::string& description,
                             std::size_t file_offset, bool at_start) {
  const std::string where = " at byte offset " + std::to_string(file_offset);
  const std::string binary = "looks like a binary file, not text (" + description + where + ")";
  if (at_start) {
    if (text.substr(0, 4) == std::string_view("PK\x03\x04", 4)) {
      return binary + ": a ZIP archive, such as an Excel .xlsx workbook; save the sheet as CSV UTF-8";
    }
    if (text.substr(0, 8) == std::string_view("\xD0\xCF\x11\xE0\xA1\xB1\x1A\xE1", 8)) {
      return binary + ": an Excel 97-2003 .xls workbook (or another OLE file); save the sheet as CSV UTF-8";
    }
    if (text.substr(0, 6) == "\x93NUMPY") return binary + ": a .npy file with a damaged header";
    if (looks_like_utf16(text)) {
      return "looks like UTF-16 text without a byte-order mark (a NUL byte every other byte" + where +
             "); save it as UTF-8 or plain CSV";
    }
  }
  const auto c = static_cast<unsigned char>(text[offset]);
  // A byte that is not UTF-8 amid text (no control characters around it): a Windows code page.
  const std::size_t window_start = offset > 4096 ? offset - 4096 : 0;
  if (c >= 0x80 && no_control_characters(text.substr(window_start, offset - window_start + 4096))) {
    const char32_t character = c >= 0xA0 ? char32_t{c} : kCp1252High[c - 0x80];
    const std::string shown = character == 0 ? std::string()
                              : " ('" + utf8_of(character) + "' in Windows-1252" + (c >= 0xA0 ? " and Latin-1)" : ")");
    return "is not UTF-8 text: byte " + hex_byte(c) + where + shown +
           " is not valid UTF-8, so the file is probably in a Windows code page (Excel's plain \"CSV\" "
           "saves in one); save it as UTF-8 (Excel: \"CSV UTF-8\")";
  }
  return binary;
}

std::size_t find_non_text_byte(std::string_view text, std::string* description) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t i = 0;
  while (i < n) {
    // Fast path over the usual printable ASCII, which is nearly all of a data file.
    while (i < n && p[i] >= 0x20 && p[i] < 0x7F) ++i;
    if (i == n) break;
    const unsigned char c = p[i];
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F) {
        *description = c == 0 ? std::string("NUL byte") : "control character " + hex_byte(c);
        return i;
      }
      ++i;
      continue;
    }
    const std::size_t length = utf8_sequence_length(p, n, i);
    if (length == 0) {
      *description = "byte " + hex_byte(c) + " that is not valid UTF-8";
      return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

TextPosition locate(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    const char c = text[i];
    // A CR directly followed by LF is one line end; the LF counts it.
    const bool cr_alone = c == '\r' && !(i + 1 < text.size() && text[i + 1] == '\n');
    if (c == '\n' || cr_alone) {
      ++line;
      line_start = i + 1;
    }
  }
  return {line, column_after(text.substr(line_start, offset - line_start))};
}

std::size_t column_after(std::string_view line_prefix) {
  std::size_t characters = 0;
  for (const char c : line_prefix) {
    if (!is_continuation(static_cast<unsigned char>(c))) ++characters;
  }
  return characters + 1;
}

ParsedNumber parse_number(std::string_view token) {
  constexpr ParsedNumber kNotANumber{NumberKind::NotANumber, 0.0};
  // from_chars follows strtod's grammar minus the '+' (and hex): accept "+1.5", but not "+-1".
  if (!token.empty() && token[0] == '+') {
    token.remove_prefix(1);
    if (token.empty() || token[0] == '+' || token[0] == '-') return kNotANumber;
  }
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value, std::chars_format::general);
  if (ptr != end || ec == std::errc::invalid_argument) return kNotANumber;
  if (ec == std::errc::result_out_of_range) {
    const bool negative = token[0] == '-';
    if (is_overflow(token)) {
      const double inf = std::numeric_limits<double>::infinity();
      return {NumberKind::Overflow, negative ? -inf : inf};
    }
    // Below the smallest denormal: the nearest double is zero, as strtod would give.
    return {NumberKind::Finite, negative ? -0.0 : 0.0};
  }
  if (std::isnan(value)) return {NumberKind::NaN, value};
  if (std::isinf(value)) return {NumberKind::Infinity, value};
  return {NumberKind::Finite, value};
}

std::string quote_token(std::string_view token) {
  constexpr std::size_t kMaxBytes = 40;
  if (token.size() <= kMaxBytes) return "'" + std::string(token) + "'";
  std::size_t cut = kMaxBytes;
  while (cut > 0 && is_continuation(static_cast<unsigned char>(token[cut]))) --cut;
  return "'" + std::string(token.substr(0, cut)) + "...'";
}

}  // namespace spdfit::io::detail
