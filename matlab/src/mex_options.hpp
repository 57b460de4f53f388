// The MATLAB/Octave front end's options: the name-value pairs of each function, read through the
// library's option tables and spelled as MATLAB spells them, the library name in CamelCase
// ('MaxIterations'), matched without regard to case as MATLAB's own functions match theirs. Nothing
// here needs MATLAB's headers (the help writer uses it); reading the pairs is in mex_pairs.hpp.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/options.hpp"
#include "spdfit/payload/identify.hpp"

namespace spdfit::matlab {

/// A function of the spdfit package whose options come from a table: which table ("fit",
/// "nearest", "solve", "identify") and the table's options it cannot take (the command line's
/// files and presentation, Python's objects, the positional arguments).
struct MatlabFunction {
  std::string_view name;   ///< "fit", "nearest", "solve", "identify" (spdfit_mex's command)
  std::string_view table;
  std::vector<std::string_view> unavailable;
};

/// A signal of spdfit.payload.identify given as a matrix name-value pair ('Quaternion', Q): its
/// library name, the field of PayloadSignals it fills (nullptr: the time vector) and its help.
struct PayloadSignal {
  std::string_view name;
  Eigen::MatrixXd payload::PayloadSignals::*matrix;
  std::string_view help;
};
const std::vector<PayloadSignal>& payload_signals();

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

}  // namespace spdfit::matlab
