#include "table_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
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

// A number as the data files' reader takes one: the whole text is a double, and a value below the
// smallest normal double (1e-308, 1e-320: subnormal, or 0 below that) is that value where stod
// reported "out of range"; an overflow (1e999) is not a number.
std::optional<double> real_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  if (errno == ERANGE && std::isinf(value)) return std::nullopt;
  return value;
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
    case OptionType::Real:
      if (const auto value = real_of(text)) return *value;
      break;
    case OptionType::RealList: {
      std::vector<double> values;
      std::size_t start = 0;
      bool ok = !text.empty();
      while (ok && start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const auto value = real_of(text.substr(start, comma - start));
        ok = value && std::isfinite(*value);
        if (ok) values.push_back(*value);
        start = comma + 1;
      }
      if (ok) return values;
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
