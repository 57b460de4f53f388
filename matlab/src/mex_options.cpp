#include "mex_options.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"
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
  // the positional arguments, the rows of a log (MATLAB indexes its arrays: A(601:end, :)), the
  // command line's presentation, and hexapod identify's --unconstrained, which MATLAB (as Python)
  // spells 'Consistent', false; payload identify and physical regress take 'Unconstrained'.
  static const std::vector<MatlabFunction> functions = {
      {"fit", "fit", {"stream", "block_rows", "noise", "a_cols", "b_cols", "rows", "rest_rows", "time_col"}},
      {"nearest", "nearest", {}},
      {"solve", "solve", {"json", "output"}},
      {"identify",
       "identify",
       {"noise", "a_cols", "b_cols", "rows", "rest_rows", "time_col", "json", "output", "unconstrained", "urdf", "precision"}},
      // The signals come as matrices (payload_signals), not as a log's columns; the URDF file is
      // the command line's.
      {"payload.identify",
       "payload",
       {"wrench_cols", "quat_cols", "rotation_cols", "gravity_cols", "accel_cols", "specific_force_cols",
        "omega_cols", "alpha_cols", "time_col", "urdf", "link_name", "precision", "json", "output"}},
      // 'NoiseCov' is a matrix (the command line's is a file).
      {"physical.regress", "regress", {"noise_cov", "json", "output"}},
  };
  return functions;
}

const std::vector<PayloadSignal>& payload_signals() {
  static const std::vector<PayloadSignal> signals = {
      {"quaternion", &payload::PayloadSignals::quaternion,
       "m x 4 quaternions (x y z w unless 'QuatOrder' is wxyz): the rotation from the sensor frame to the world."},
      {"rotation", &payload::PayloadSignals::rotation, "m x 9 rotation matrices, row-major."},
      {"gravity_in_sensor", &payload::PayloadSignals::gravity, "m x 3 gravity in the sensor frame (m/s^2)."},
      {"accel", &payload::PayloadSignals::accel,
       "m x 3 kinematic acceleration of the sensor's origin in the sensor frame (m/s^2)."},
      {"specific_force", &payload::PayloadSignals::specific_force,
       "m x 3 IMU specific force (gravity included: no orientation needed)."},
      {"omega", &payload::PayloadSignals::omega, "m x 3 angular velocity (rad/s): the inertia enters the model."},
      {"alpha", &payload::PayloadSignals::alpha,
       "m x 3 angular acceleration (rad/s^2); without it, omega's central differences in 'Time'."},
      {"time", nullptr, "m x 1 times (s)."},
  };
  return signals;
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
    case OptionType::Names: return "text or cell array of text";
    case OptionType::Range: return "[lo hi] or text LO:HI";
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

// The tables' help is written for the command line and Python: MATLAB's words for their values
// (a vector, not comma-separated numbers; [] for None; true and false), whole words only.
std::string matlab_words(std::string text) {
  static const std::vector<std::pair<std::string, std::string>> words = {
      {"(comma-separated)", "(a vector)"}, {"None", "[]"}, {"True", "true"}, {"False", "false"}};
  const auto word_char = [&text](std::size_t i) {
    return i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_');
  };
  for (const auto& [from, to] : words) {
    std::size_t at = text.find(from);
    while (at != std::string::npos) {
      const bool whole = (at == 0 || !word_char(at - 1)) && !word_char(at + from.size());
      if (whole) text.replace(at, from.size(), to);
      at = text.find(from, at + (whole ? to.size() : 1));
    }
  }
  return text;
}

template <typename Request>
std::vector<MatlabOption> help_of(const std::vector<OptionSpec<Request>>& table, const MatlabFunction& function) {
  std::vector<MatlabOption> out;
  for (const OptionSpec<Request>& spec : table) {
    if (!takes(function, spec.name, spec.positional)) continue;
    out.push_back({camel_case(spec.name), type_name(spec.type, spec.choices),
                   matlab_words(spell_options(spec.help, Frontend::Matlab)), matlab_words(std::string(spec.default_text))});
  }
  return out;
}

}  // namespace

std::vector<MatlabOption> option_help(std::string_view name) {
  const MatlabFunction& function = matlab_function(name);
  if (function.table == "fit") return help_of(fit_option_table(), function);
  if (function.table == "nearest") return help_of(nearest_option_table(), function);
  if (function.table == "solve") return help_of(solve_option_table(), function);
  if (function.table == "payload") {
    std::vector<MatlabOption> out;
    for (const PayloadSignal& signal : payload_signals()) {
      out.push_back({camel_case(signal.name), "matrix", std::string(signal.help), ""});
    }
    for (MatlabOption& o : help_of(payload::identify_option_table(), function)) out.push_back(std::move(o));
    return out;
  }
  if (function.table == "regress") {
    std::vector<MatlabOption> out = help_of(physical::regress_option_table(), function);
    out.push_back({"NoiseCov", "matrix",
                   "The covariance of the noise in one sample's d outputs (d x d): the rows come in samples of d, "
                   "each sample's residual weighted by its inverse.",
                   ""});
    return out;
  }
  return help_of(hexapod::identify_option_table(), function);
}

}  // namespace spdfit::matlab
