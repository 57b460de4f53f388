// Internal: parsing the small JSON input files (hexapod geometries, rigid-body inertias) with
// errors that name the file, the line and the column, and bounded memory on hostile input.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace spdfit::io::detail {

/// Nesting beyond which a small input file is refused before parsing (its formats need 3 levels):
/// keeps the parser's memory and stack bounded.
inline constexpr int kMaxJsonNesting = 64;

/// Parses `text` as JSON. Throws io::DataError naming `source`: when the text is longer than
/// `max_bytes` ("... are accepted for <what>"), nests more than kMaxJsonNesting levels (with line
/// and column of the bracket that opens the level too many; "<what> needs <levels_needed>"), or is
/// not valid JSON (with line and column where the parser has them). The first two are checked
/// before parsing. Cost O(size of text).
nlohmann::json parse_json_document(const std::string& text, const std::string& source, std::size_t max_bytes,
                                   const std::string& what, int levels_needed);

/// A JSON value described for a message: "an array of 4 entries", "the string \"x\"", "null", ...
std::string describe_json(const nlohmann::json& value);

}  // namespace spdfit::io::detail
