#include "table_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace spdfit::cli {

namespace {

// The integer `text` stands for ("12", "-3", "1e3"), or nothing.
std::optional<std::int64_t> integer_of(const std::string& text) {
  try {
    std::size_t used = 0;
    const long long value = std::stoll(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    // Exactly an integer, and within the range of a 64-bit integer (2^63 itself is not).
    if (used == text.size() && value == std::floor(value) && std::abs(value) < 9.2e18) {
      return static_cast<std::int64_t>(value);
    }
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

}  // namespace

CLI::Validator range_validator(const NumberRange& range, bool integer) {
  const std::string what = range.describe(integer);
  const std::string article = integer ? "an " : "a ";
  return CLI::Validator(
      [range, integer, what, article](std::string& text) -> std::string {
        if (integer) {
          const std::optional<std::int64_t> value = integer_of(text);
          if (value && range.contains(static_cast<double>(*value))) return "";
        } else {
          try {
            std::size_t used = 0;
            const double value = std::stod(text, &used);
            if (used == text.size() && std::isfinite(value) && range.contains(value)) return "";
          } catch (const std::exception&) {
          }
        }
        return "'" + text + "' is not " + article + what;
      },
      what);
}

std::string choices_text(const std::vector<std::string_view>& choices) {
  std::string text;
  for (std::string_view c : choices) text += (text.empty() ? "" : "|") + std::string(c);
  return text;
}

std::string cli_help(std::string_view help, std::string_view default_text) {
  std::string text = spell_options(help, Frontend::Cli);
  if (!default_text.empty()) text += " (default " + std::string(default_text) + ")";
  return text;
}

void throw_usage(const std::exception& error) {
  const Code code = code_of(error);
  throw UsageError(spell_options(error.what(), Frontend::Cli), tier(code) == Tier::Usage ? code : Code::Argument);
}

OptionValue parse_option_text(OptionType type, std::string_view spelling, const std::string& text) {
  switch (type) {
    case OptionType::Integer:
      if (const auto value = integer_of(text)) return *value;
      break;
    // The library's parser of numbers (options.hpp), as the other front ends': a value below the
    // smallest normal double (1e-308) is that value, an overflow (1e999) is Inf.
    case OptionType::Real:
      if (const auto values = comma_separated_numbers(text); values && values->size() == 1) return values->front();
      break;
    case OptionType::RealList: {
      const auto values = comma_separated_numbers(text);
      if (values && std::all_of(values->begin(), values->end(), [](double v) { return std::isfinite(v); })) {
        return *values;
      }
      throw UsageError(std::string(spelling) + ": '" + text +
                       "' is not a number or a comma-separated list of numbers (one per column)");
    }
    default:
      return text;
  }
  throw UsageError(std::string(spelling) + ": '" + text + "' is not " +
                   (type == OptionType::Integer ? "an integer" : "a number"));
}

}  // namespace spdfit::cli
