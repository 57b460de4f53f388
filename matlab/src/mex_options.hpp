// The MATLAB/Octave front end's options: the name-value pairs of each function, read through the
// library's option tables and spelled as MATLAB spells them, the library name in CamelCase
// ('MaxIterations'), matched without regard to case as MATLAB's own functions match theirs. Each
// value is read by its table type; nothing here knows an option by name.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mex.h"
#include "spdfit/options.hpp"

namespace spdfit::matlab {

/// One name-value pair as the gateway received it: the name as typed and the value's array.
struct NameValue {
  std::string name;
  const mxArray* value = nullptr;
};

/// A function of the spdfit package whose options come from a table: which table ("fit",
/// "nearest", "solve", "identify") and the table's options it cannot take (the command line's
/// files and presentation, Python's objects, the positional arguments).
struct MatlabFunction {
  std::string_view name;   ///< "fit", "nearest", "solve", "identify" (spdfit_mex's command)
  std::string_view table;
  std::vector<std::string_view> unavailable;
};

/// The package's functions.
const std::vector<MatlabFunction>& matlab_functions();
/// The function named `name`; std::invalid_argument when there is none.
const MatlabFunction& matlab_function(std::string_view name);

/// A MATLAB function's option, as its help text lists it.
struct MatlabOption {
  std::string name;  ///< 'MaxIterations'
  std::string type;  ///< "logical", "integer", "real", "text", "vector", "matrix", "one of ..."
  std::string help;  ///< the table's help text, option names spelled for MATLAB
  std::string default_text;
};

/// The options of `function` for its generated help text, in the table's order.
std::vector<MatlabOption> option_help(std::string_view function);

/// Whether the spec of option `spec` is one `function` takes.
bool takes(const MatlabFunction& function, std::string_view name, bool positional);

/// The value of a pair for an option of `type`: a logical or 0/1 scalar (Flag, Boolean), an
/// integer-valued scalar, a real scalar, a character vector (Text, Choice, File, Columns, Rows,
/// Geometry: a file's name), a numeric vector (RealList, Vector), a numeric matrix or a file's name
/// (Matrix). UsageError naming `name` for a value of the wrong kind; nothing for [] (the default).
std::optional<OptionValue> read_value(OptionType type, const std::string& name, const mxArray* value);

/// Sets each pair in `request` through `table` (the spec whose CamelCase name matches, without
/// regard to case, among those `function` takes) and returns the library names given (those not
/// left at []). OptionError for a name the function does not take, a value the library refuses, a
/// name given twice, or [] for an option without a default.
template <typename Request>
std::vector<std::string_view> set_pairs(Request& request, const std::vector<OptionSpec<Request>>& table,
                                        const std::vector<NameValue>& pairs, const MatlabFunction& function);

/// The names `function` takes, for the message about a name it does not ("MaxIterations, ...").
template <typename Request>
std::string option_names(const std::vector<OptionSpec<Request>>& table, const MatlabFunction& function) {
  std::string names;
  for (const OptionSpec<Request>& spec : table) {
    if (takes(function, spec.name, spec.positional)) names += (names.empty() ? "" : ", ") + camel_case(spec.name);
  }
  return names;
}

bool same_name(std::string_view a, std::string_view b);

template <typename Request>
std::vector<std::string_view> set_pairs(Request& request, const std::vector<OptionSpec<Request>>& table,
                                        const std::vector<NameValue>& pairs, const MatlabFunction& function) {
  std::vector<std::string_view> given;
  for (const NameValue& pair : pairs) {
    const OptionSpec<Request>* found = nullptr;
    for (const OptionSpec<Request>& spec : table) {
      if (takes(function, spec.name, spec.positional) && same_name(camel_case(spec.name), pair.name)) found = &spec;
    }
    if (found == nullptr) {
      throw OptionError("spdfit." + std::string(function.name == "identify" ? "hexapod.identify" : function.name) +
                            " has no option '" + pair.name + "' (its options: " + option_names(table, function) + ")",
                        Code::UnknownOption);
    }
    for (std::string_view g : given) {
      if (g == found->name) {
        throw OptionError("`" + std::string(found->name) + "` is given twice", Code::OptionConflict,
                          std::string(found->name));
      }
    }
    const std::optional<OptionValue> value = read_value(found->type, camel_case(found->name), pair.value);
    if (!value) {
      if (!found->nullable) {
        throw OptionError("`" + std::string(found->name) + "` cannot be [] (it has no default to stand for)",
                          Code::OptionType, std::string(found->name));
      }
      continue;
    }
    set_option(request, *found, *value);
    // A flag set to false is not given ('Physical', false is the default).
    if (found->type == OptionType::Flag && !std::get<bool>(*value)) continue;
    given.push_back(found->name);
  }
  return given;
}

}  // namespace spdfit::matlab
