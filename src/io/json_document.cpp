#include "io/json_document.hpp"

#include <algorithm>
#include <utility>

#include "spdfit/io.hpp"

namespace spdfit::io::detail {

namespace {

using nlohmann::json;

// 1-based line and column of a byte offset, for parse errors.
std::pair<std::size_t, std::size_t> line_and_column(const std::string& text, std::size_t byte) {
  byte = std::min(byte, text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < byte; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Throws a DataError at the first '[' or '{' (outside strings) that opens level kMaxJsonNesting + 1.
void check_nesting(const std::string& text, const std::string& source, const std::string& what, int levels_needed) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting) {
        const auto [line, column] = line_and_column(text, i + 1);
        throw DataError(source, line, column,
                        "JSON nested more than " + std::to_string(kMaxJsonNesting) + " levels deep; " + what +
                            " needs " + std::to_string(levels_needed));
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

}  // namespace

json parse_json_document(const std::string& text, const std::string& source, std::size_t max_bytes,
                         const std::string& what, int levels_needed) {
  if (text.size() > max_bytes) {
    throw DataError(source, 0, 0,
                    "is " + std::to_string(text.size()) + " bytes long; at most " + std::to_string(max_bytes) +
                        " are accepted for " + what);
  }
  check_nesting(text, source, what, levels_needed);
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    const auto [line, column] = line_and_column(text, e.byte);
    std::string problem = e.what();
    // nlohmann's message starts "[json.exception.parse_error.101] parse error at line ...: "; keep
    // the part after the last ": " that explains the problem.
    const std::size_t colon = problem.find("parse error");
    if (colon != std::string::npos) problem = problem.substr(colon);
    throw DataError(source, line, column, "not valid JSON: " + problem);
  } catch (const json::exception& e) {
    // The parser reports a number beyond the double range ("1e999") as out_of_range, without a
    // position; keep its explanation after the "[json.exception...] " tag.
    std::string problem = e.what();
    const std::size_t tag_end = problem.find("] ");
    if (tag_end != std::string::npos) problem = problem.substr(tag_end + 2);
    throw DataError(source, 0, 0, "not valid JSON: " + problem);
  }
}

std::string describe_json(const json& value) {
  if (value.is_array()) return "an array of " + std::to_string(value.size()) + " entries";
  if (value.is_object()) return "an object";
  if (value.is_string()) return "the string " + value.dump();
  if (value.is_boolean()) return value.dump();
  if (value.is_null()) return "null";
  return "the number " + value.dump();
}

}  // namespace spdfit::io::detail
