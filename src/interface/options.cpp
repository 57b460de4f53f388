// Checking an option value against its table entry, and the texts of ranges and values in messages.
#include "spdfit/options.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>

#include <algorithm>
#include <cctype>

namespace spdfit {

namespace {

// The shortest text that reads back as `value` ("0.95", "1e-08", "1000000").
std::string number_text(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15) return std::to_string(static_cast<long long>(value));
  char buffer[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace

std::string NumberRange::describe(bool integer) const {
  const bool bounded_below = min > -std::numeric_limits<double>::infinity();
  const bool bounded_above = max < std::numeric_limits<double>::infinity();
  const std::string noun = integer ? "integer" : bounded_above ? "number" : "finite number";
  if (bounded_below && bounded_above) {
    if (!integer && min == 0.0 && max == 1.0 && min_open && max_open) return "fraction strictly between 0 and 1";
    return noun + " in " + (min_open ? "(" : "[") + number_text(min) + ", " + number_text(max) +
           (max_open ? ")" : "]");
  }
  if (bounded_below) return noun + (min_open ? " > " : " >= ") + number_text(min);
  if (bounded_above) return noun + (max_open ? " < " : " <= ") + number_text(max);
  return noun;
}

std::pair<double, double> parse_range(const std::string& text, std::string_view option) {
  const auto number = [](const std::string& t, double& value) {
    std::size_t used = 0;
    try {
      value = std::stod(t, &used);
    } catch (const std::exception&) {
      return false;
    }
    return used == t.size() && std::isfinite(value);
  };
  const std::size_t colon = text.find(':');
  double lo = 0.0, hi = 0.0;
  if (colon == std::string::npos || !number(text.substr(0, colon), lo) || !number(text.substr(colon + 1), hi)) {
    throw OptionError("`" + std::string(option) + "` '" + text + "' is not a range LO:HI of two numbers", Code::OptionValue,
                      std::string(option));
  }
  return {lo, hi};
}

std::string range_text(double lo, double hi) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g:%.17g", lo, hi);
  return buffer;
}

std::string value_text(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return number_text(*d);
  if (const std::string* s = std::get_if<std::string>(&value)) return "'" + *s + "'";
  if (std::holds_alternative<std::shared_ptr<const NoiseModel>>(value)) return "a noise model";
  if (const GeometryInput* g = std::get_if<GeometryInput>(&value)) {
    return g->path.empty() ? std::string("a geometry") : "'" + g->path + "'";
  }
  if (const MatrixInput* m = std::get_if<MatrixInput>(&value)) {
    if (m->from_file()) return "'" + m->path + "'";
    return "a " + std::to_string(m->values.rows()) + "x" + std::to_string(m->values.cols()) + " matrix";
  }
  const auto& list = std::get<std::vector<double>>(value);
  std::string text;
  for (double v : list) text += (text.empty() ? "" : ",") + number_text(v);
  return "[" + text + "]";
}

std::optional<std::vector<double>> comma_separated_numbers(std::string_view text) {
  std::vector<double> values;
  std::size_t start = 0;
  if (text.find_first_not_of(" \t") == std::string_view::npos) return std::nullopt;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part(text.substr(start, comma - start));
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (end == part.c_str()) return std::nullopt;
    while (*end == ' ' || *end == '\t') ++end;
    if (*end != '\0') return std::nullopt;
    values.push_back(v);
    start = comma + 1;
  }
  return values;
}

namespace {

bool same_text(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

OptionValue checked_option_value(std::string_view name, OptionType type, const NumberRange& range,
                                 const std::vector<std::string_view>& choices, OptionValue value) {
  const auto fail = [&](Code code, const std::string& expected) {
    throw OptionError("`" + std::string(name) + "` must be " + expected + ", got " + value_text(value), code,
                      std::string(name));
  };
  const auto wrong_type = [&](const std::string& expected) { fail(Code::OptionType, expected); };
  const auto out_of_range = [&](const std::string& expected) { fail(Code::OptionValue, expected); };
  switch (type) {
    case OptionType::Flag:
    case OptionType::Boolean:
      if (!std::holds_alternative<bool>(value)) wrong_type("true or false");
      break;
    case OptionType::Integer:
      if (!std::holds_alternative<std::int64_t>(value)) wrong_type("an integer");
      if (!range.contains(static_cast<double>(std::get<std::int64_t>(value)))) {
        out_of_range("an " + range.describe(true));
      }
      break;
    case OptionType::Real: {
      if (std::holds_alternative<std::int64_t>(value)) value = static_cast<double>(std::get<std::int64_t>(value));
      if (!std::holds_alternative<double>(value)) wrong_type("a real number");
      const double v = std::get<double>(value);
      if (!(std::abs(v) <= std::numeric_limits<double>::max()) || !range.contains(v)) {
        out_of_range("a " + range.describe(false));
      }
      break;
    }
    case OptionType::Text:
    case OptionType::File:
      if (!std::holds_alternative<std::string>(value)) wrong_type(type == OptionType::File ? "a file name" : "text");
      break;
    case OptionType::Names:
      if (!std::holds_alternative<std::string>(value)) wrong_type("names");
      if (std::get<std::string>(value).find_first_not_of(" ,\t") == std::string::npos) out_of_range("one name or more");
      break;
    case OptionType::Range:
      if (!std::holds_alternative<std::string>(value)) wrong_type("a range LO:HI");
      if (std::get<std::string>(value).find(':') == std::string::npos) out_of_range("a range LO:HI of two numbers");
      break;
    case OptionType::Columns:
    case OptionType::Rows:
      if (!std::holds_alternative<std::string>(value)) wrong_type("a selection as text");
      if (std::get<std::string>(value).find_first_not_of(" \t") == std::string::npos) {
        out_of_range("a selection, not empty text");
      }
      break;
    case OptionType::Choice: {
      if (!std::holds_alternative<std::string>(value)) wrong_type("text");
      std::string list;
      for (std::size_t i = 0; i < choices.size(); ++i) {
        if (same_text(choices[i], std::get<std::string>(value))) return std::string(choices[i]);
        list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + ("'" + std::string(choices[i]) + "'");
      }
      out_of_range("one of " + list);
      break;
    }
    case OptionType::RealList:
      if (!std::holds_alternative<std::vector<double>>(value)) wrong_type("a list of real numbers");
      if (std::get<std::vector<double>>(value).empty()) {
        out_of_range("one number or a list of numbers, not an empty list");
      }
      for (double v : std::get<std::vector<double>>(value)) {
        if (!(std::abs(v) <= std::numeric_limits<double>::max()) || !range.contains(v)) {
          out_of_range("a list of numbers, each a " + range.describe(false));
        }
      }
      break;
    case OptionType::Vector:
      if (!std::holds_alternative<std::vector<double>>(value)) wrong_type("a list of real numbers");
      break;
    case OptionType::Noise: {
      const auto* model = std::get_if<std::shared_ptr<const NoiseModel>>(&value);
      if (model == nullptr || *model == nullptr) wrong_type("a noise model");
      break;
    }
    case OptionType::Geometry: {
      if (const std::string* path = std::get_if<std::string>(&value)) value = GeometryInput{*path, nullptr};
      const GeometryInput* g = std::get_if<GeometryInput>(&value);
      if (g == nullptr) wrong_type("a hexapod geometry (or its file)");
      if (!g->given()) out_of_range("a geometry or a file name, not empty text");
      break;
    }
    case OptionType::Matrix: {
      // Text: comma-separated numbers are the values (one row), anything else a file's name.
      if (const std::string* text = std::get_if<std::string>(&value)) {
        MatrixInput input;
        if (const std::optional<std::vector<double>> numbers = comma_separated_numbers(*text)) {
          input.values = Eigen::Map<const Eigen::RowVectorXd>(numbers->data(), Eigen::Index(numbers->size()));
        } else {
          input.path = *text;
        }
        value = std::move(input);
      }
      const MatrixInput* m = std::get_if<MatrixInput>(&value);
      if (m == nullptr) wrong_type("a matrix (or a file of one)");
      if (!m->from_file() && m->values.size() == 0) out_of_range("a matrix with entries, not an empty one");
      break;
    }
  }
  return value;
}

}  // namespace spdfit
