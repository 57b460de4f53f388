// The MATLAB/Octave front end's options: the name-value pairs of each function, read through the
// library's option tables (fit_option_table, nearest_option_table) and spelled as MATLAB spells
// them, the library name in CamelCase ('MaxIterations'), matched without regard to case as
// MATLAB's own functions match theirs.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit::matlab {

/// One name-value pair as the gateway received it: the name as typed and a reader of its value.
struct NameValue {
  std::string name;
  OptionValue value;
  bool empty = false;  ///< the value was [] (the option's default, where the option allows it)
  Eigen::MatrixXd matrix;  ///< the value of a matrix option (ValueShape::Matrix)
};

/// How a value of `type` is read from MATLAB: a logical or 0/1 scalar, an integer-valued scalar, a
/// real scalar, a character vector, or a numeric vector.
enum class ValueShape { Boolean, Integer, Real, Text, List, Matrix };
ValueShape value_shape(OptionType type);

/// How option `name` (the library's) is read from MATLAB: its table type's shape, except the noise
/// model's rest rows and covariances, which the command line reads from files and MATLAB takes as
/// matrices ('RestA', 'RestB', 'NoiseCovA', 'NoiseCovB').
ValueShape matlab_shape(std::string_view name, OptionType type);

/// A MATLAB function's option, as its help text lists it.
struct MatlabOption {
  std::string name;  ///< 'MaxIterations'
  std::string type;  ///< "logical", "integer", "real", "text", "vector"
  std::string help;  ///< the table's help text, option names spelled for MATLAB
  std::string default_text;
};

/// The options of `function` ("fit": the fit table without the stream's, which reads files;
/// "nearest": the nearest table; "solve"; "identify"; "payload.identify"; "physical.regress"), for
/// its generated help text.
std::vector<MatlabOption> option_help(std::string_view function);

/// The shape each name-value pair of `function` ("fit", "nearest", "solve") needs, by the name a
/// user typed (case-insensitive); throws OptionError for a name the function does not take.
ValueShape option_shape(std::string_view function, std::string_view typed_name);

/// The request for spdfit.fit with `method` and the pairs given: each value checked against the
/// table's type and range, each option checked against the method and the table's rules. Throws
/// OptionError, spelled for MATLAB.
FitRequest fit_request(std::string_view method, const std::vector<NameValue>& pairs);

/// The fit's options for data with n columns in A and d in B: request.options with the noise
/// model the pairs gave (rest rows or covariances as matrices, standard deviations as numbers).
/// Throws std::invalid_argument or OptionError for a model the data or the library refuse.
FitOptions fit_options(const FitRequest& request, const std::vector<NameValue>& pairs, Eigen::Index n,
                       Eigen::Index d);
NearestRequest nearest_request(const std::vector<NameValue>& pairs);

/// What spdfit.hexapod.identify was asked for: the fit's options for every estimator, and with
/// 'Physical' the physical fit's (its table's, plus those it shares with the fit's table), the
/// geometry file, the truth and the stiffness.
struct IdentifyRequest {
  FitRequest fit;
  std::vector<NameValue> fit_pairs;         ///< the pairs of the fit's table (for fit_options)
  std::vector<std::string_view> fit_given;  ///< the fit table's options given (library names)
  bool physical = false;
  hexapod::PhysicalOptions physical_options;
  std::string geometry;                     ///< the geometry file (hexapod model --write-geometry)
  Eigen::MatrixXd truth, stiffness;         ///< empty: not given
};
IdentifyRequest identify_request(const std::vector<NameValue>& pairs);

/// What spdfit.payload.identify was asked for: the signals besides the wrench ('Quaternion',
/// 'Rotation', 'GravityInSensor', 'Accel', 'SpecificForce', 'Omega', 'Alpha', 'Time', as matrices)
/// and the options of payload identify's table (but the log file's column options and the URDF
/// file's, which read and write files).
struct PayloadRequest {
  payload::PayloadSignals signals;
  payload::IdentifyRequest request;
};
PayloadRequest payload_request(const std::vector<NameValue>& pairs);

/// spdfit.physical.regress's options: the regress table's ('NoiseCov' a matrix, 'Prior' a JSON file of bodies).
physical::RegressRequest regress_request(const std::vector<NameValue>& pairs);
LinearSystemOptions solve_options(const std::vector<NameValue>& pairs);

}  // namespace spdfit::matlab
