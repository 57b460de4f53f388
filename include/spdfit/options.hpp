// Options declared once: a table of each request's options (name, type, default, range, help,
// which methods take them) from which the command line registers its options, Python binds its
// keyword arguments and MATLAB its name-value pairs, and by which all of them check what a user
// gave. This is the layer above the core: the core's option structs (FitOptions, ...) validate
// themselves in plain C++ (is_valid) and know no front end; the tables here add the spellings.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "spdfit/outcome.hpp"
#include "spdfit/spelling.hpp"

namespace spdfit {

class NoiseModel;
namespace hexapod {
struct Geometry;
}

/// An option's type, which decides how a front end reads a value.
enum class OptionType {
  Flag,     ///< true when given (the command line's flag without a value; Python and MATLAB: a bool)
  Boolean,  ///< a bool value
  Integer,  ///< an integer within the option's range
  Real,     ///< a finite real number within the option's range
  Text,     ///< a string
  RealList, ///< real numbers: one, or one per column (the command line: comma-separated)
  Vector,   ///< n real numbers (the command line reads them from a file: one column or one row)
  /// A noise model (noise_model.hpp): Python's spdfit.NoiseModel. The command line has none:
  /// it gives a model's sources as options of their own (files and numbers).
  Noise,
  Choice,   ///< one of the spec's `choices` (matched without regard to case; stored as the table spells it)
  /// Names, as comma-separated text (the command line's "spde,procrustes"); Python also takes a
  /// sequence of str and MATLAB a cell array of char. Stored as the comma-separated text; the
  /// workflow checks the names.
  Names,
  File,     ///< a file's path (the command line and MATLAB: text; Python: str or os.PathLike)
  /// A matrix: a file on the command line (any format a data file takes), an array in Python and
  /// MATLAB (or a path as text). The value is a MatrixInput; the workflow reads the file.
  Matrix,
  /// Columns of a table (io::ColumnSelection's syntax: names, 1-based positions, ranges, lists:
  /// "acc1:acc6", "2:7", "1,3:5,F1"). Python also takes a list of labels or 0-based positions.
  Columns,
  /// Rows of a table: 1-based inclusive ranges and lists ("601:", "1:5000,7001:").
  Rows,
  /// An interval of two numbers, stored as the text "LO:HI" (the command line's form; the
  /// workflow parses and checks it). Python also takes a pair of numbers (lo, hi), MATLAB [lo hi];
  /// both are written with 17 significant digits, so the numbers arrive exactly.
  Range,
  /// A hexapod geometry (hexapod/geometry.hpp): a file on the command line and in MATLAB, an
  /// spdfit.hexapod.Geometry (or a path) in Python. The value is a GeometryInput.
  Geometry,
};

/// A matrix given as a file (the command line) or as values (Python, MATLAB; the command line's
/// comma-separated numbers, one row): one of the two.
struct MatrixInput {
  std::string path;        ///< a file any data reader takes (FILE:NAME names an array), or empty
  Eigen::MatrixXd values;  ///< the matrix, when given as values
  bool from_file() const { return !path.empty(); }
  bool given() const { return from_file() || values.size() > 0; }
};

/// A hexapod geometry given as a file (read_geometry) or as an object: one of the two, or neither.
struct GeometryInput {
  std::string path;
  std::shared_ptr<const hexapod::Geometry> value;
  bool given() const { return !path.empty() || value != nullptr; }
};

/// The values an option can take, as a front end hands them over.
using OptionValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>,
                                 std::shared_ptr<const NoiseModel>, MatrixInput, GeometryInput>;

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
  /// A Choice's values, as the table spells them (the first is the default unless `default_text` says).
  std::vector<std::string_view> choices;
  /// The command line's positional argument (its `cli` is the name in usage text, "A"); Python and
  /// MATLAB take it as a positional argument of their own.
  bool positional = false;
  /// Must be given (a positional argument without which the command cannot run).
  bool required = false;
  /// Whether the option takes effect for a request (its method, its kind of repair); nullptr for
  /// every request. Given where it does not apply, the option is an error (misplaced_option).
  std::function<bool(const Request&)> applies;
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
  std::function<void(Request&, const OptionValue&)> set;
  /// The request's value, for the range check of a request built in C++ and for the defaults
  /// that front ends show; nothing for an option without a default.
  std::function<std::optional<OptionValue>(const Request&)> get;
};

/// The numbers of `text` separated by commas ("1e6", "1,2.5,3"; spaces around each allowed), or
/// nothing when it is not such a list (a file's name).
std::optional<std::vector<double>> comma_separated_numbers(std::string_view text);

/// The text of an option value for messages ("0", "2.5", "yes").
std::string value_text(const OptionValue& value);

/// A Range option's value "LO:HI" as two finite numbers; OptionError (Code::OptionValue) naming
/// `option` (a library name: `psi_range`) otherwise. No order is required: the workflow says which.
std::pair<double, double> parse_range(const std::string& text, std::string_view option);
/// The text of a Range value: "LO:HI" with 17 significant digits (exact for doubles).
std::string range_text(double lo, double hi);

/// The entry of `table` named `name` (the library's name), or nullptr.
template <typename Request>
const OptionSpec<Request>* find_option(const std::vector<OptionSpec<Request>>& table, std::string_view name) {
  for (const OptionSpec<Request>& spec : table) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

/// `value` checked against an option's type, range and choices (an integer is accepted where a
/// real is expected, and becomes one; a choice matched without regard to case becomes the table's
/// spelling; a Columns or Rows selection's syntax is checked). Throws OptionError naming the option
/// `name`: Code::OptionType for a value of another type, Code::OptionValue for one out of range.
OptionValue checked_option_value(std::string_view name, OptionType type, const NumberRange& range,
                                 const std::vector<std::string_view>& choices, OptionValue value);

/// `value` checked against the option's type and range (checked_option_value).
template <typename Request>
OptionValue checked_value(const OptionSpec<Request>& spec, OptionValue value) {
  return checked_option_value(spec.name, spec.type, spec.range, spec.choices, std::move(value));
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
        throw OptionError("give `" + std::string(spec.name) + "` or `" + std::string(other) + "`, not both",
                          Code::OptionConflict, std::string(spec.name));
      }
    }
    if (spec.needs.empty()) continue;
    bool met = false;
    for (std::string_view other : spec.needs) met = met || is_given(other);
    if (met) continue;
    if (!spec.needs_message.empty()) {
      throw OptionError(std::string(spec.needs_message), Code::OptionConflict, std::string(spec.name));
    }
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
    throw OptionError("`" + std::string(spec.name) + "` needs " + list, Code::OptionConflict, std::string(spec.name));
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

/// `table` with each entry's `needs` and `excludes` cut to the options the table has (a command
/// that takes some of another table's options: hexapod identify has the bootstrap's threads but
/// no stream). An entry whose `needs` were cut keeps its message only when all remain.
template <typename Request>
std::vector<OptionSpec<Request>> trimmed_rules(std::vector<OptionSpec<Request>> table) {
  const auto has = [&table](std::string_view name) { return find_option(table, name) != nullptr; };
  for (OptionSpec<Request>& spec : table) {
    std::vector<std::string_view> needs, excludes;
    for (std::string_view n : spec.needs) {
      if (has(n)) needs.push_back(n);
    }
    for (std::string_view e : spec.excludes) {
      if (has(e)) excludes.push_back(e);
    }
    if (needs.size() != spec.needs.size()) spec.needs_message = {};
    spec.needs = std::move(needs);
    spec.excludes = std::move(excludes);
  }
  return table;
}

/// The entries of `table` (options of an Inner request) as options of an Outer request that holds
/// an Inner at `member` (a command's request holding the fit's: hexapod identify's FitRequest),
/// those named in `names` only (all when empty), in the table's order. Their `applies` is dropped
/// unless `keep_applies` (a command that runs every method takes an option that applies to one).
template <typename Outer, typename Inner>
std::vector<OptionSpec<Outer>> lifted_options(const std::vector<OptionSpec<Inner>>& table, Inner Outer::*member,
                                              const std::vector<std::string_view>& names = {},
                                              bool keep_applies = false) {
  std::vector<OptionSpec<Outer>> out;
  for (const OptionSpec<Inner>& inner : table) {
    bool wanted = names.empty();
    for (std::string_view n : names) wanted = wanted || n == inner.name;
    if (!wanted) continue;
    OptionSpec<Outer> spec;
    spec.name = inner.name;
    spec.cli = inner.cli;
    spec.python = inner.python;
    spec.type = inner.type;
    spec.value_name = inner.value_name;
    spec.help = inner.help;
    spec.default_text = inner.default_text;
    spec.nullable = inner.nullable;
    spec.range = inner.range;
    spec.choices = inner.choices;
    spec.positional = inner.positional;
    spec.required = inner.required;
    if (keep_applies && inner.applies) {
      spec.applies = [applies = inner.applies, member](const Outer& o) { return applies(o.*member); };
    }
    spec.applies_to = inner.applies_to;
    spec.needs = inner.needs;
    spec.needs_message = inner.needs_message;
    spec.excludes = inner.excludes;
    if (inner.set) spec.set = [set = inner.set, member](Outer& o, const OptionValue& v) { set(o.*member, v); };
    if (inner.get) spec.get = [get = inner.get, member](const Outer& o) { return get(o.*member); };
    out.push_back(std::move(spec));
  }
  return out;
}

}  // namespace spdfit
