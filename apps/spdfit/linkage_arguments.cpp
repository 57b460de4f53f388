#include "linkage_arguments.hpp"

#include <cmath>
#include <sstream>

#include "cli.hpp"
#include "spdfit/linkage/synthesize_request.hpp"
#include "spdfit/spelling.hpp"

namespace spdfit::cli {

namespace {

bool parse_number(const std::string& text, double& value) {
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && std::isfinite(value);
}

}  // namespace

std::pair<double, double> parse_range(const std::string& text, const std::string& option) {
  try {
    return linkage::parse_angle_range(text, option);
  } catch (const OptionError& e) {
    throw UsageError(spell_options(e.what(), Frontend::Cli), e.code());
  }
}

std::vector<double> parse_list(const std::string& text, std::size_t count, const std::string& option) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    double value = 0.0;
    if (!parse_number(item, value)) throw UsageError(option + ": '" + item + "' is not a number");
    values.push_back(value);
  }
  if (values.size() != count) {
    throw UsageError(option + " needs " + std::to_string(count) + " comma-separated numbers, got " +
                     std::to_string(values.size()));
  }
  return values;
}

}  // namespace spdfit::cli
