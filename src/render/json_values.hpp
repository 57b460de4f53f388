// Internal: numbers, vectors and matrices to and from nlohmann::json in either JsonStyle, and
// reading a document's fields with errors that name what is missing. The renderers of each
// result type (render/*.cpp) are built from these.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "spdfit/outcome.hpp"
#include "spdfit/render.hpp"

namespace spdfit::detail {

using Json = nlohmann::json;
/// The documents whose keys keep the order written (the physical fits, the payload, inertias).
using OrderedJson = nlohmann::ordered_json;

/// A number: finite as itself; +-inf and NaN as null (Contract: JSON has no literal for them) or
/// as the strings "inf", "-inf", "nan" (Exact). Contract is what the command line's documents
/// use, and the default.
Json number_json(double value, JsonStyle style = JsonStyle::Contract);
/// A vector as an array of numbers; a matrix as an array of its rows.
Json vector_json(const Eigen::VectorXd& v, JsonStyle style = JsonStyle::Contract);
Json matrix_json(const Eigen::MatrixXd& M, JsonStyle style = JsonStyle::Contract);
/// The columns of B as an array of vectors (bases: null spaces, ranges).
Json columns_json(const Eigen::MatrixXd& B, JsonStyle style);

/// The document's text: Contract indented by 2 with a final newline (what the command line
/// prints), Exact on one line.
std::string dump(const Json& document, JsonStyle style);

/// Reads what the functions above wrote, in either style (null reads as NaN). Each throws
/// std::invalid_argument naming `what` (the class and field) when the value has the wrong type.
double number_from(const Json& value, const std::string& what);
Eigen::VectorXd vector_from(const Json& value, const std::string& what);
/// `rows` fixes the row count of a matrix with no columns written (an empty array has none).
Eigen::MatrixXd matrix_from(const Json& value, const std::string& what, Eigen::Index rows = 0);
Eigen::MatrixXd columns_from(const Json& value, const std::string& what, Eigen::Index rows);

/// The field `key` of `object`; std::invalid_argument naming `type` and the key when it is missing.
const Json& field(const Json& object, const char* key, const std::string& type);
/// The field, when present.
const Json* optional_field(const Json& object, const char* key);
/// A text's document; std::invalid_argument naming `type` when it is not JSON or not an object.
Json parse_object(const std::string& text, const std::string& type);

/// field() read as a value of type T (a bool, an integer or a string).
template <typename T>
T value_from(const Json& object, const char* key, const std::string& type) {
  const Json& value = field(object, key, type);
  try {
    return value.get<T>();
  } catch (const nlohmann::json::exception&) {
    throw std::invalid_argument(type + ": '" + key + "' has the wrong type (" + value.type_name() + ")");
  }
}

/// A result's warnings: their texts as "warnings" and their codes' names as "warning_codes"
/// (in a json or an ordered_json object).
template <typename Object>
void put_warnings(Object& object, const std::vector<Warning>& warnings) {
  Object texts = Object::array(), codes = Object::array();
  for (const Warning& w : warnings) {
    texts.push_back(w.text);
    codes.push_back(std::string(code_info(w.code).name));
  }
  object["warnings"] = std::move(texts);
  object["warning_codes"] = std::move(codes);
}
/// What put_warnings wrote; without "warning_codes" (a document written before codes), each
/// warning's code is Code::Warning.
std::vector<Warning> warnings_from(const Json& object, const std::string& type);

/// An optional number: written when present, read as absent when the key is missing.
void put_optional(Json& object, const char* key, const std::optional<double>& value, JsonStyle style);
std::optional<double> optional_number_from(const Json& object, const char* key, const std::string& type);

}  // namespace spdfit::detail
