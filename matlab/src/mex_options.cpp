#include "mex_options.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "mex_arrays.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/solve_request.hpp"

namespace spdfit::matlab {

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

const std::vector<MatlabFunction>& matlab_functions() {
  // What each function cannot take: the stream's options and the columns of one file (MATLAB
  // passes arrays), Python's NoiseModel object (MATLAB gives the model's numbers and matrices),
  // the positional arguments, the command line's presentation, and the command line's spelling of
  // a setting MATLAB has under its own name (--unconstrained is 'Consistent', false).
  static const std::vector<MatlabFunction> functions = {
      {"fit", "fit", {"stream", "block_rows", "noise", "a_cols", "b_cols"}},
      {"nearest", "nearest", {}},
      {"solve", "solve", {"json", "output"}},
      {"identify", "identify", {"noise", "a_cols", "b_cols", "json", "output", "unconstrained"}},
  };
  return functions;
}

const MatlabFunction& matlab_function(std::string_view name) {
  for (const MatlabFunction& f : matlab_functions()) {
    if (f.name == name) return f;
  }
  throw std::invalid_argument("no MATLAB function named '" + std::string(name) + "'");
}

bool takes(const MatlabFunction& function, std::string_view name, bool positional) {
  if (positional) return false;
  return std::find(function.unavailable.begin(), function.unavailable.end(), name) == function.unavailable.end();
}

namespace {

std::string type_name(OptionType type, const std::vector<std::string_view>& choices) {
  switch (type) {
    case OptionType::Flag:
    case OptionType::Boolean: return "logical";
    case OptionType::Integer: return "integer";
    case OptionType::Real: return "real";
    case OptionType::Text:
    case OptionType::Columns:
    case OptionType::Rows: return "text";
    case OptionType::File:
    case OptionType::Geometry: return "file name";
    case OptionType::RealList:
    case OptionType::Vector: return "vector";
    case OptionType::Matrix: return "matrix";
    case OptionType::Noise: return "noise model";
    case OptionType::Choice: {
      std::string text;
      for (std::size_t i = 0; i < choices.size(); ++i) {
        text += (i == 0 ? "'" : i + 1 == choices.size() ? " or '" : ", '") + std::string(choices[i]) + "'";
      }
      return text;
    }
  }
  return "real";
}

template <typename Request>
std::vector<MatlabOption> help_of(const std::vector<OptionSpec<Request>>& table, const MatlabFunction& function) {
  std::vector<MatlabOption> out;
  for (const OptionSpec<Request>& spec : table) {
    if (!takes(function, spec.name, spec.positional)) continue;
    out.push_back({camel_case(spec.name), type_name(spec.type, spec.choices), spell_options(spec.help, Frontend::Matlab),
                   std::string(spec.default_text)});
  }
  return out;
}

}  // namespace

std::vector<MatlabOption> option_help(std::string_view name) {
  const MatlabFunction& function = matlab_function(name);
  if (function.table == "fit") return help_of(fit_option_table(), function);
  if (function.table == "nearest") return help_of(nearest_option_table(), function);
  if (function.table == "solve") return help_of(solve_option_table(), function);
  return help_of(hexapod::identify_option_table(), function);
}

}  // namespace spdfit::matlab
