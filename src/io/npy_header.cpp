#include "npy_header.hpp"

#include <limits>
#include <map>
#include <utility>

#include "spdfit/io.hpp"
#include "text_scan.hpp"

namespace spdfit::io::detail {

namespace {

// .npy errors have no line or column; positions, if any, are in the message.
[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw DataError(source, 0, 0, problem);
}

// A Python literal as written by repr(): all a .npy header dict holds.
struct PyValue {
  enum class Kind { String, Bool, None, Int, Tuple, List };
  Kind kind = Kind::None;
  std::string text;            // kString: the contents; kInt: the digits as written
  bool flag = false;           // kBool
  std::uint64_t integer = 0;   // kInt
  bool negative = false;       // kInt
  bool too_large = false;      // kInt: does not fit in 64 bits
  std::vector<PyValue> items;  // kTuple, kList
};

// Recursive descent over the header text. Nesting is capped so that a hostile header of a
// million '(' cannot overflow the stack.
class PyLiteralParser {
 public:
  PyLiteralParser(std::string_view text, const std::string& source) : s_(text), source_(source) {}

  std::map<std::string, PyValue> parse_dict() {
    std::map<std::string, PyValue> dict;
    skip_space();
    expect('{', "the header does not start with '{'");
    while (true) {
      skip_space();
      if (peek() == '}') break;
      const PyValue key = parse_value(0);
      if (key.kind != PyValue::Kind::String) fail("a key is not a string");
      skip_space();
      expect(':', "expected ':' after " + quote_token(key.text));
      PyValue value = parse_value(0);
      if (!dict.emplace(key.text, std::move(value)).second) {
        fail(quote_token(key.text) + " appears twice");
      }
      skip_space();
      if (peek() == ',') {
        ++pos_;
      } else if (peek() != '}') {
        fail("expected ',' or '}' after the value of " + quote_token(key.text));
      }
    }
    ++pos_;
    skip_space();
    if (pos_ < s_.size()) fail("unexpected text after the closing '}'");
    return dict;
  }

 private:
  static constexpr int kMaxDepth = 16;

  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }

  void skip_space() {
    while (pos_ < s_.size() &&
           (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t' || s_[pos_] == '\r')) {
      ++pos_;
    }
  }

  void expect(char c, const std::string& problem) {
    if (peek() != c) fail(problem);
    ++pos_;
  }

  bool consume_word(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  PyValue parse_value(int depth) {
    if (depth > kMaxDepth) fail("nested too deeply");
    skip_space();
    PyValue value;
    const char c = peek();
    if (c == '\'' || c == '"') {
      value.kind = PyValue::Kind::String;
      value.text = parse_string();
    } else if (c == '(' || c == '[') {
      value.kind = c == '(' ? PyValue::Kind::Tuple : PyValue::Kind::List;
      value.items = parse_sequence(c == '(' ? ')' : ']', depth);
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      parse_integer(&value);
    } else if (consume_word("True")) {
      value.kind = PyValue::Kind::Bool;
      value.flag = true;
    } else if (consume_word("False")) {
      value.kind = PyValue::Kind::Bool;
    } else if (consume_word("None")) {
      value.kind = PyValue::Kind::None;
    } else {
      fail(pos_ < s_.size() ? "unexpected character " + describe(c) : std::string("it ends early"));
    }
    return value;
  }

  std::string parse_string() {
    const char quote = s_[pos_++];
    std::string text;
    while (true) {
      if (pos_ >= s_.size()) fail("a string has no closing quote");
      char c = s_[pos_++];
      if (c == quote) return text;
      if (c == '\\') {
        if (pos_ >= s_.size()) fail("a string has no closing quote");
        c = s_[pos_++];
      }
      text += c;
    }
  }

  std::vector<PyValue> parse_sequence(char close, int depth) {
    ++pos_;
    std::vector<PyValue> items;
    while (true) {
      skip_space();
      if (peek() == close) break;
      items.push_back(parse_value(depth + 1));
      skip_space();
      if (peek() == ',') {
        ++pos_;
      } else if (peek() != close) {
        fail(std::string("expected ',' or '") + close + "'");
      }
    }
    ++pos_;
    return items;
  }

  // Python 2 wrote long integers with a trailing 'L': old files have shapes like (12L, 6L).
  void parse_integer(PyValue* value) {
    value->kind = PyValue::Kind::Int;
    if (peek() == '-') {
      value->negative = true;
      ++pos_;
    }
    const std::size_t start = pos_;
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
    while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') {
      const auto digit = static_cast<std::uint64_t>(s_[pos_] - '0');
      if (value->integer > (kMax - digit) / 10) value->too_large = true;
      if (!value->too_large) value->integer = value->integer * 10 + digit;
      ++pos_;
    }
    if (pos_ == start) fail("'-' is not followed by digits");
    value->text = std::string(s_.substr(start, pos_ - start));
    if (peek() == 'L' || peek() == 'l') ++pos_;
  }

  // A character for a message; the header of a damaged file may hold any byte.
  static std::string describe(char c) {
    if (c >= 0x20 && c < 0x7F) return std::string("'") + c + "'";
    const char* digits = "0123456789ABCDEF";
    const auto byte = static_cast<unsigned char>(c);
    return std::string("byte 0x") + digits[byte >> 4] + digits[byte & 0xF];
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw DataError(source_, 0, 0, "malformed .npy header: " + problem);
  }

  std::string_view s_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

std::uint32_t read_little_endian(std::string_view bytes, std::size_t offset, std::size_t size) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < size; ++k) {
    value |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[offset + k])) << (8 * k);
  }
  return value;
}

}  // namespace

NpyHeader parse_npy_header(std::string_view bytes, const std::string& source) {
  if (bytes.substr(0, kNpyMagic.size()) != kNpyMagic) {
    fail(source, "not a .npy file (it does not start with the .npy magic bytes)");
  }
  if (bytes.size() < kNpyMagic.size() + 2) {
    fail(source, "truncated .npy file: the header is incomplete");
  }
  const auto major = static_cast<unsigned char>(bytes[6]);
  const auto minor = static_cast<unsigned char>(bytes[7]);
  if (!(major >= 1 && major <= 3 && minor == 0)) {
    fail(source, "unsupported .npy format version " + std::to_string(major) + "." + std::to_string(minor) +
                     " (1.0, 2.0 and 3.0 are supported)");
  }
  // Version 1.0 stores the header length in 2 bytes; 2.0 and 3.0 (UTF-8 header) in 4.
  const std::size_t length_size = major == 1 ? 2 : 4;
  const std::size_t header_start = 8 + length_size;
  if (bytes.size() < header_start) fail(source, "truncated .npy file: the header is incomplete");
  const std::size_t header_length = read_little_endian(bytes, 8, length_size);
  if (header_length > bytes.size() - header_start) {
    fail(source, "truncated .npy file: the header claims " + std::to_string(header_length) +
                     " bytes, but only " + std::to_string(bytes.size() - header_start) + " follow");
  }

  // NumPy itself refuses headers this long (numpy.lib.format's max_header_size); the header of
  // a float64 array takes about 120 bytes. The cap also bounds the parser's work and memory.
  constexpr std::size_t kMaxHeaderLength = 10000;
  if (header_length > kMaxHeaderLength) {
    fail(source, "malformed .npy header: it is " + std::to_string(header_length) + " bytes long (at most " +
                     std::to_string(kMaxHeaderLength) + " are accepted)");
  }

  PyLiteralParser parser(bytes.substr(header_start, header_length), source);
  std::map<std::string, PyValue> dict = parser.parse_dict();
  const auto entry = [&dict, &source](const std::string& key) -> const PyValue& {
    const auto it = dict.find(key);
    if (it == dict.end()) fail(source, "malformed .npy header: no '" + key + "' entry");
    return it->second;
  };

  NpyHeader header;
  header.data_offset = header_start + header_length;
  const PyValue& descr = entry("descr");
  if (descr.kind == PyValue::Kind::String) {
    header.descr = descr.text;
  } else if (descr.kind == PyValue::Kind::List) {
    header.structured = true;
  } else {
    fail(source, "malformed .npy header: 'descr' is not a string");
  }
  const PyValue& fortran_order = entry("fortran_order");
  if (fortran_order.kind != PyValue::Kind::Bool) {
    fail(source, "malformed .npy header: 'fortran_order' is not True or False");
  }
  header.fortran_order = fortran_order.flag;
  const PyValue& shape = entry("shape");
  if (shape.kind != PyValue::Kind::Tuple) {
    fail(source, "malformed .npy header: 'shape' is not a tuple");
  }
  for (const PyValue& dimension : shape.items) {
    if (dimension.kind != PyValue::Kind::Int || dimension.negative) {
      fail(source, "malformed .npy header: 'shape' holds something other than sizes");
    }
    if (dimension.too_large) fail(source, "shape dimension " + quote_token(dimension.text) + " is too large");
    header.shape.push_back(dimension.integer);
  }
  return header;
}

std::string format_shape(const std::vector<std::uint64_t>& shape) {
  std::string text = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) {
    if (k > 0) text += ", ";
    text += std::to_string(shape[k]);
  }
  if (shape.size() == 1) text += ',';
  return text + ")";
}

}  // namespace spdfit::io::detail
