#include "text_scan.hpp"

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

}  // namespace

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
  constexpr ParsedNumber kNotANumber{NumberKind::kNotANumber, 0.0};
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
      return {NumberKind::kOverflow, negative ? -inf : inf};
    }
    // Below the smallest denormal: the nearest double is zero, as strtod would give.
    return {NumberKind::kFinite, negative ? -0.0 : 0.0};
  }
  if (std::isnan(value)) return {NumberKind::kNaN, value};
  if (std::isinf(value)) return {NumberKind::kInfinity, value};
  return {NumberKind::kFinite, value};
}

std::string quote_token(std::string_view token) {
  constexpr std::size_t kMaxBytes = 40;
  if (token.size() <= kMaxBytes) return "'" + std::string(token) + "'";
  std::size_t cut = kMaxBytes;
  while (cut > 0 && is_continuation(static_cast<unsigned char>(token[cut]))) --cut;
  return "'" + std::string(token.substr(0, cut)) + "...'";
}

}  // namespace spdfit::io::detail
