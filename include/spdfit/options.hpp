// Options declared once: a table of each request's options (name, type, default, range, help,
// which methods take them) from which the command line registers its options, Python binds its
// keyword arguments and MATLAB its name-value pairs, and by which all of them check what a user
// gave. fit_request.hpp and nearest_request.hpp hold the two tables.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace spdfit {

class NoiseModel;

/// The front ends, each of which spells an option its own way: the library by its name
/// (`max_iterations`), the command line as "--max-iter", Python as max_iter, MATLAB as
/// 'MaxIterations' (the library name in CamelCase).
enum class Frontend { Library, Cli, Python, Matlab };

/// An option's type, which decides how a front end reads a value.
enum class OptionType {
  Flag,     ///< true when given (the command line's flag without a value; Python and MATLAB: a bool)
  Boolean,  ///< a bool value
  Integer,  ///< an integer within the option's range
  Real,     ///< a finite real number within the option's range
  Text,     ///< a string (a file name)
  RealList, ///< real numbers: one, or one per column (the command line: comma-separated)
  Vector,   ///< n real numbers (the command line reads them from a file: one column or one row)
  /// A noise model (noise_model.hpp): Python's spdfit.NoiseModel. The command line has none:
  /// it gives a model's sources as options of their own (files and numbers).
  Noise,
};

/// The values an option can take, as a front end hands them over.
using OptionValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>,
                                 std::shared_ptr<const NoiseModel>>;

/// The interval an integer or real option's value must lie in.
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false, max_open = false;

  bool contains(double value) const {
    return (min_open ? value > min : value >= min) && (max_open ? value < max : value <= max);
  }
  /// What a value must be, for messages and help: "a finite number > 0", "a number in [0, 1)",
  /// "an integer in [1, 1000000]" (`integer` chooses the noun).
  std::string describe(bool integer) const;
};

/// A misused option: a value of the wrong type or out of range, an option the chosen method does
/// not take, or a combination the request's rules forbid. The message names options by their
/// library names in backticks (`max_iterations`); a front end shows it through spell_options.
struct OptionError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// One option of a request type (FitRequest, NearestRequest).
template <typename Request>
struct OptionSpec {
  std::string_view name;    ///< the library's name: the field it sets, snake_case
  std::string_view cli;     ///< the command line's spelling ("--rank-tol"); empty: not offered there
  std::string_view python;  ///< Python's keyword ("rank_tolerance"); empty: not offered there
  OptionType type = OptionType::Real;
  std::string_view value_name;  ///< the placeholder in usage text ("N", "NUMBER", "FILE")
  /// What it does, for the command line's help, Python's docstrings and MATLAB's help; other
  /// options named by their library names in backticks.
  std::string_view help;
  /// The default as people read it ("200", "max(m, n) eps"); empty where there is none to show.
  std::string_view default_text;
  /// Whether a front end's "no value" (Python's None, MATLAB's []) stands for the default. False
  /// for counts and switches (bootstrap, threads, flags), whose default value front ends show
  /// and whose "no value" is more likely a mistake: then a type error.
  bool nullable = true;
  NumberRange range;  ///< Integer, Real and each value of a RealList
  /// Whether the option takes effect for a request (its method, its kind of repair); nullptr for
  /// every request. Given where it does not apply, the option is an error (misplaced_option).
  bool (*applies)(const Request&) = nullptr;
  /// Who takes it, for the message of an option given where it does not apply: "the iterative
  /// methods" (the method names are added), or a whole sentence after "needs".
  std::string_view applies_to;
  /// The option takes effect only together with one of these (by library name); given without
  /// any of them it is an error, with `needs_message` (backticked names) or a default message.
  std::vector<std::string_view> needs;
  std::string_view needs_message;
  /// Options it cannot be given with (by library name).
  std::vector<std::string_view> excludes;
  /// Stores a value of the option's type, already checked against `range`, in the request.
  void (*set)(Request&, const OptionValue&) = nullptr;
  /// The request's value, for the range check of a request built in C++ and for the defaults
  /// that front ends show; nothing for an option without a default.
  std::optional<OptionValue> (*get)(const Request&) = nullptr;
};

/// The spelling of option `name` in `frontend`: the command line's and Python's from the tables
/// (fit_option_table, nearest_option_table), MATLAB's the name in CamelCase; a name no table has
/// follows the tables' convention ("--" and the name with hyphens on the command line, the name
/// in Python).
std::string spell_option(std::string_view name, Frontend frontend);

/// `message` with every backticked library name of an option (`max_iterations`) replaced by its
/// spelling in `frontend` ("--max-iter" on the command line). Backticks in the library's messages
/// are for option names only. The library's own spelling is the name without backticks.
std::string spell_options(std::string_view message, Frontend frontend);

/// MATLAB's spelling of a library name: "max_iterations" -> "MaxIterations".
std::string camel_case(std::string_view name);

/// The text of an option value for messages ("0", "2.5", "yes").
std::string value_text(const OptionValue& value);

/// The entry of `table` named `name` (the library's name), or nullptr.
template <typename Request>
const OptionSpec<Request>* find_option(const std::vector<OptionSpec<Request>>& table, std::string_view name) {
  for (const OptionSpec<Request>& spec : table) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

/// `value` checked against the option's type and range (an integer is accepted where a real is
/// expected, and becomes one). Throws OptionError naming the option.
template <typename Request>
OptionValue checked_value(const OptionSpec<Request>& spec, OptionValue value) {
  const auto wrong = [&](const std::string& expected) {
    throw OptionError("`" + std::string(spec.name) + "` must be " + expected + ", got " + value_text(value));
  };
  switch (spec.type) {
    case OptionType::Flag:
    case OptionType::Boolean:
      if (!std::holds_alternative<bool>(value)) wrong("true or false");
      break;
    case OptionType::Integer:
      if (!std::holds_alternative<std::int64_t>(value)) wrong("an integer");
      if (!spec.range.contains(static_cast<double>(std::get<std::int64_t>(value)))) {
        wrong("an " + spec.range.describe(true));
      }
      break;
    case OptionType::Real: {
      if (std::holds_alternative<std::int64_t>(value)) value = static_cast<double>(std::get<std::int64_t>(value));
      if (!std::holds_alternative<double>(value)) wrong("a real number");
      const double v = std::get<double>(value);
      if (!(std::abs(v) <= std::numeric_limits<double>::max()) || !spec.range.contains(v)) {
        wrong("a " + spec.range.describe(false));
      }
      break;
    }
    case OptionType::Text:
      if (!std::holds_alternative<std::string>(value)) wrong("text");
      break;
    case OptionType::RealList:
      if (!std::holds_alternative<std::vector<double>>(value)) wrong("a list of real numbers");
      if (std::get<std::vector<double>>(value).empty()) wrong("one number or a list of numbers, not an empty list");
      for (double v : std::get<std::vector<double>>(value)) {
        if (!(std::abs(v) <= std::numeric_limits<double>::max()) || !spec.range.contains(v)) {
          wrong("a list of numbers, each a " + spec.range.describe(false));
        }
      }
      break;
    case OptionType::Vector:
      if (!std::holds_alternative<std::vector<double>>(value)) wrong("a list of real numbers");
      break;
    case OptionType::Noise: {
      const auto* model = std::get_if<std::shared_ptr<const NoiseModel>>(&value);
      if (model == nullptr || *model == nullptr) wrong("a noise model");
      break;
    }
  }
  return value;
}

/// Checks `value` (checked_value) and stores it in `request`. Throws OptionError naming the option.
template <typename Request>
void set_option(Request& request, const OptionSpec<Request>& spec, const OptionValue& value) {
  spec.set(request, checked_value(spec, value));
}

/// The message for option `spec` given in `request`, where it does not apply (its `applies`),
/// naming who takes it; nothing when it applies. `requests` are one request per method or kind,
/// whose names are listed where the option applies (may be empty).
template <typename Request>
std::optional<std::string> misplaced_option(const OptionSpec<Request>& spec, const Request& request,
                                            const std::vector<std::pair<std::string, Request>>& requests,
                                            std::string_view here) {
  if (spec.applies == nullptr || spec.applies(request)) return std::nullopt;
  std::string names;
  for (const auto& [name, other] : requests) {
    if (spec.applies(other)) names += (names.empty() ? "" : ", ") + name;
  }
  std::string text = "`" + std::string(spec.name) + "` applies to ";
  if (spec.applies_to.empty()) {
    text += names;
  } else {
    text += std::string(spec.applies_to) + (names.empty() ? "" : " (" + names + ")");
  }
  return text + ", not to " + std::string(here);
}

/// Checks the rules among the options a user gave (`given`, library names, in any order): each
/// one's `needs` and `excludes`. Throws OptionError with the first rule broken; its list of what
/// an option needs leaves out the options in `unavailable` (those a front-end function cannot
/// take: Python's nearest_spd has no `corr`).
template <typename Request>
void check_option_combination(const std::vector<OptionSpec<Request>>& table,
                              const std::vector<std::string_view>& given,
                              const std::vector<std::string_view>& unavailable = {}) {
  const auto is_given = [&](std::string_view name) {
    for (std::string_view g : given) {
      if (g == name) return true;
    }
    return false;
  };
  for (const OptionSpec<Request>& spec : table) {
    if (!is_given(spec.name)) continue;
    for (std::string_view other : spec.excludes) {
      if (is_given(other)) {
        throw OptionError("give `" + std::string(spec.name) + "` or `" + std::string(other) + "`, not both");
      }
    }
    if (spec.needs.empty()) continue;
    bool met = false;
    for (std::string_view other : spec.needs) met = met || is_given(other);
    if (met) continue;
    if (!spec.needs_message.empty()) throw OptionError(std::string(spec.needs_message));
    std::vector<std::string_view> possible;
    for (std::string_view need : spec.needs) {
      bool out = false;
      for (std::string_view u : unavailable) out = out || u == need;
      if (!out) possible.push_back(need);
    }
    std::string list;
    for (std::size_t i = 0; i < possible.size(); ++i) {
      list += (i == 0 ? "" : i + 1 == possible.size() ? " or " : ", ") + ("`" + std::string(possible[i]) + "`");
    }
    throw OptionError("`" + std::string(spec.name) + "` needs " + list);
  }
}

/// Checks every option's value in a request built in C++ against its range (the rule set_option
/// applies to a value a user gives). False, with `error` naming the option as OptionError does
/// (its library name in backticks, for spell_options), when one is out of range.
template <typename Request>
bool options_in_range(const Request& request, const std::vector<OptionSpec<Request>>& table,
                      std::string* error) {
  for (const OptionSpec<Request>& spec : table) {
    if (spec.get == nullptr) continue;
    const std::optional<OptionValue> value = spec.get(request);
    if (!value) continue;
    try {
      checked_value(spec, *value);
    } catch (const OptionError& e) {
      if (error) *error = e.what();
      return false;
    }
  }
  return true;
}

}  // namespace spdfit
