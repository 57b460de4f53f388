#include "render/json_values.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace spdfit::detail {

Json number_json(double value, JsonStyle style) {
  if (std::isfinite(value)) return value;
  if (style == JsonStyle::Contract) return nullptr;
  return std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf";
}

Json vector_json(const Eigen::VectorXd& v, JsonStyle style) {
  Json out = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number_json(v(i), style));
  return out;
}

Json matrix_json(const Eigen::MatrixXd& M, JsonStyle style) {
  Json rows = Json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    Json row = Json::array();
    for (Eigen::Index j = 0; j < M.cols(); ++j) row.push_back(number_json(M(i, j), style));
    rows.push_back(std::move(row));
  }
  return rows;
}

Json columns_json(const Eigen::MatrixXd& B, JsonStyle style) {
  Json out = Json::array();
  for (Eigen::Index j = 0; j < B.cols(); ++j) out.push_back(vector_json(B.col(j), style));
  return out;
}

std::string dump(const Json& document, JsonStyle style) {
  return style == JsonStyle::Contract ? document.dump(2) + "\n" : document.dump();
}

double number_from(const Json& value, const std::string& what) {
  if (value.is_number()) return value.get<double>();
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (value.is_string()) {
    const std::string& text = value.get_ref<const std::string&>();
    if (text == "inf") return std::numeric_limits<double>::infinity();
    if (text == "-inf") return -std::numeric_limits<double>::infinity();
    if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
  }
  throw std::invalid_argument(what + ": expected a number, not " + value.dump());
}

Eigen::VectorXd vector_from(const Json& value, const std::string& what) {
  if (!value.is_array()) throw std::invalid_argument(what + ": expected an array of numbers");
  Eigen::VectorXd v(static_cast<Eigen::Index>(value.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) v(i) = number_from(value[static_cast<std::size_t>(i)], what);
  return v;
}

Eigen::MatrixXd matrix_from(const Json& value, const std::string& what, Eigen::Index rows) {
  if (!value.is_array()) throw std::invalid_argument(what + ": expected an array of rows");
  if (value.empty()) return Eigen::MatrixXd(rows, 0);
  const auto m = static_cast<Eigen::Index>(value.size());
  const Json& first = value.front();
  if (!first.is_array()) throw std::invalid_argument(what + ": expected an array of rows");
  const auto n = static_cast<Eigen::Index>(first.size());
  Eigen::MatrixXd M(m, n);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Json& row = value[static_cast<std::size_t>(i)];
    if (!row.is_array() || static_cast<Eigen::Index>(row.size()) != n) {
      throw std::invalid_argument(what + ": row " + std::to_string(i + 1) + " does not have " + std::to_string(n) +
                                  " entries like the first");
    }
    for (Eigen::Index j = 0; j < n; ++j) M(i, j) = number_from(row[static_cast<std::size_t>(j)], what);
  }
  return M;
}

Eigen::MatrixXd columns_from(const Json& value, const std::string& what, Eigen::Index rows) {
  if (!value.is_array()) throw std::invalid_argument(what + ": expected an array of vectors");
  Eigen::MatrixXd B(rows, static_cast<Eigen::Index>(value.size()));
  for (Eigen::Index j = 0; j < B.cols(); ++j) {
    const Eigen::VectorXd column = vector_from(value[static_cast<std::size_t>(j)], what);
    if (column.size() != rows) {
      throw std::invalid_argument(what + ": vector " + std::to_string(j + 1) + " has " +
                                  std::to_string(column.size()) + " entries, not " + std::to_string(rows));
    }
    B.col(j) = column;
  }
  return B;
}

const Json& field(const Json& object, const char* key, const std::string& type) {
  const auto found = object.find(key);
  if (found == object.end()) throw std::invalid_argument(type + ": the JSON has no '" + key + "'");
  return *found;
}

const Json* optional_field(const Json& object, const char* key) {
  const auto found = object.find(key);
  return found == object.end() ? nullptr : &*found;
}

Json parse_object(const std::string& text, const std::string& type) {
  Json document = Json::parse(text, nullptr, false);
  if (document.is_discarded()) throw std::invalid_argument(type + ": the text is not JSON");
  if (!document.is_object()) throw std::invalid_argument(type + ": the JSON is not an object");
  return document;
}

void put_optional(Json& object, const char* key, const std::optional<double>& value, JsonStyle style) {
  if (value) object[key] = number_json(*value, style);
}

std::optional<double> optional_number_from(const Json& object, const char* key, const std::string& type) {
  const Json* value = optional_field(object, key);
  if (!value) return std::nullopt;
  return number_from(*value, type + " '" + key + "'");
}

std::vector<Warning> warnings_from(const Json& object, const std::string& type) {
  const std::vector<std::string> texts = value_from<std::vector<std::string>>(object, "warnings", type);
  std::vector<std::string> names;
  if (optional_field(object, "warning_codes") != nullptr) {
    names = value_from<std::vector<std::string>>(object, "warning_codes", type);
    if (names.size() != texts.size()) {
      throw std::invalid_argument(type + ": 'warning_codes' has " + std::to_string(names.size()) +
                                  " entries but 'warnings' " + std::to_string(texts.size()));
    }
  }
  std::vector<Warning> out;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    Code code = Code::Warning;
    if (!names.empty()) {
      const std::optional<Code> named = code_named(names[i]);
      if (!named) throw std::invalid_argument(type + ": 'warning_codes' has an unknown code '" + names[i] + "'");
      code = *named;
    }
    out.emplace_back(code, texts[i]);
  }
  return out;
}

}  // namespace spdfit::detail
