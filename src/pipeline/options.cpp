// Spelling options per front end, and the texts of ranges and values in messages.
#include "spdfit/options.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>

#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/nearest_request.hpp"

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

template <typename Request>
std::optional<std::string> spelling_in(const std::vector<OptionSpec<Request>>& table, std::string_view name,
                                       Frontend frontend) {
  const OptionSpec<Request>* spec = find_option(table, name);
  if (spec == nullptr) return std::nullopt;
  const std::string_view spelled = frontend == Frontend::Cli ? spec->cli : spec->python;
  return std::string(spelled.empty() ? name : spelled);
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

std::string camel_case(std::string_view name) {
  std::string out;
  bool upper = true;
  for (char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

std::string spell_option(std::string_view name, Frontend frontend) {
  if (frontend == Frontend::Library || (frontend == Frontend::Python && name.empty())) return std::string(name);
  if (frontend == Frontend::Matlab) return camel_case(name);
  if (auto spelled = spelling_in(fit_option_table(), name, frontend)) return *spelled;
  if (auto spelled = spelling_in(nearest_option_table(), name, frontend)) return *spelled;
  if (auto spelled = spelling_in(hexapod::physical_option_table(), name, frontend)) return *spelled;
  // An option of no table (the linkage's alpha and beta) follows the convention the tables keep:
  // "--max-iter" on the command line, the name in Python.
  if (frontend == Frontend::Python) return std::string(name);
  std::string cli = "--";
  for (char c : name) cli += c == '_' ? '-' : c;
  return cli;
}

std::string spell_options(std::string_view message, Frontend frontend) {
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const std::size_t open = message.find('`', i);
    const std::size_t close = open == std::string_view::npos ? open : message.find('`', open + 1);
    if (close == std::string_view::npos) {
      out += message.substr(i);
      break;
    }
    out += message.substr(i, open - i);
    out += spell_option(message.substr(open + 1, close - open - 1), frontend);
    i = close + 1;
  }
  return out;
}

std::string value_text(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return number_text(*d);
  if (const std::string* s = std::get_if<std::string>(&value)) return "'" + *s + "'";
  if (std::holds_alternative<std::shared_ptr<const NoiseModel>>(value)) return "a noise model";
  if (const auto* m = std::get_if<Eigen::MatrixXd>(&value)) {
    return "a " + std::to_string(m->rows()) + "x" + std::to_string(m->cols()) + " matrix";
  }
  const auto& list = std::get<std::vector<double>>(value);
  std::string text;
  for (double v : list) text += (text.empty() ? "" : ",") + number_text(v);
  return "[" + text + "]";
}

}  // namespace spdfit
