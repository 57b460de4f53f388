#include "mex_options.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <optional>

#include "spdfit/inertia_repair.hpp"

namespace spdfit::matlab {

namespace {

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// The fit options spdfit.fit takes: those of the in-memory fit. The stream's read files, as do
// a_cols and b_cols (columns of one file), and `noise` is Python's NoiseModel object: MATLAB gives
// the model's numbers and matrices instead.
bool fit_takes(std::string_view name) {
  return name != "stream" && name != "block_rows" && name != "noise" && name != "a_cols" && name != "b_cols";
}

// The noise options whose command-line value is a file, which MATLAB takes as a matrix.
bool matrix_option(std::string_view name) {
  return name == "rest_a" || name == "rest_b" || name == "noise_cov_a" || name == "noise_cov_b";
}

// spdfit.solve's options (LinearSystemOptions), which have no table of their own yet.
struct SolveOption {
  std::string_view name;
  std::string_view help;
  std::string_view default_text;
};
constexpr SolveOption kSolveOptions[] = {
    {"threshold",
     "Relative singular-value cut-off for the rank, applied to A with its columns scaled to unit norm: sigma_i "
     "counts as zero when sigma_i <= Threshold * sigma_max.",
     "max(m, n) eps"},
    {"rcond_warning", "The reciprocal condition number (of the column-scaled A) below which a warning says that A "
                      "is ill-conditioned.",
     "1e-12"},
};

// spdfit.hexapod.identify's own options besides the fit's and the physical fit's tables.
struct IdentifyOption {
  std::string_view name;
  ValueShape shape;
  std::string_view help;
};
constexpr IdentifyOption kIdentifyOptions[] = {
    {"physical", ValueShape::Boolean,
     "Also identify the payload's mass, centre of mass and inertia, physically consistent, from the geometry "
     "(needs 'Geometry')."},
    {"geometry", ValueShape::Text, "The hexapod's geometry file (spdfit hexapod model --write-geometry G.json)."},
    {"truth", ValueShape::Matrix, "The true M_p (n x n), to report each estimate's error."},
    {"stiffness", ValueShape::Matrix, "The strut stiffness matrix K (n x n), to report the modes in Hz."},
};

const IdentifyOption* identify_option(std::string_view typed) {
  for (const IdentifyOption& o : kIdentifyOptions) {
    if (same_name(camel_case(o.name), typed)) return &o;
  }
  return nullptr;
}

// spdfit.payload.identify's signals, given as matrices, and the table's options it takes: not the
// log file's column selections nor the URDF file's (MATLAB passes arrays and gets a struct).
constexpr const char* kPayloadSignals[] = {"quaternion", "rotation", "gravity_in_sensor", "accel",
                                           "specific_force", "omega", "alpha", "time"};
constexpr const char* kPayloadSignalHelp[] = {
    "m x 4 quaternions (x y z w unless 'QuatOrder' is wxyz): the rotation from the sensor frame to the world.",
    "m x 9 rotation matrices, row-major.",
    "m x 3 gravity in the sensor frame (m/s^2).",
    "m x 3 kinematic acceleration of the sensor's origin in the sensor frame (m/s^2).",
    "m x 3 IMU specific force (gravity included: no orientation needed).",
    "m x 3 angular velocity (rad/s): the inertia enters the model.",
    "m x 3 angular acceleration (rad/s^2); without it, omega's central differences in 'Time'.",
    "m x 1 times (s)."};

bool payload_takes(std::string_view name) {
  const std::string_view left_out[] = {"wrench_cols", "quat_cols", "rotation_cols", "gravity_cols", "accel_cols",
                                       "specific_force_cols", "omega_cols", "alpha_cols", "time_col", "urdf",
                                       "link_name", "precision", "unconstrained"};
  for (std::string_view n : left_out)
    if (n == name) return false;
  return true;
}

int payload_signal(std::string_view typed) {
  for (int k = 0; k < 8; ++k) {
    if (same_name(camel_case(kPayloadSignals[k]), typed)) return k;
  }
  return -1;
}

bool regress_takes(std::string_view name) { return name != "unconstrained"; }

const OptionSpec<hexapod::PhysicalOptions>* physical_option(std::string_view typed) {
  for (const auto& spec : hexapod::physical_option_table()) {
    if (same_name(camel_case(spec.name), typed)) return &spec;
  }
  return nullptr;
}

std::string type_name(ValueShape shape) {
  switch (shape) {
    case ValueShape::Boolean: return "logical";
    case ValueShape::Integer: return "integer";
    case ValueShape::Real: return "real";
    case ValueShape::Text: return "text";
    case ValueShape::List: return "vector";
    case ValueShape::Matrix: return "matrix";
  }
  return "real";
}

// The help of a matrix option, whose table help speaks of the command line's file.
std::string matrix_help(std::string_view name) {
  if (name == "rest_a") {
    return "Rows of A recorded at rest (accelerations zero), at least 2 rows with A's columns: Sigma_A is their "
           "sample covariance about their mean. Needs 'RestB'.";
  }
  if (name == "rest_b") {
    return "Rows of B recorded at rest, as many as 'RestA''s (forces constant): Sigma_B is their sample "
           "covariance about their mean.";
  }
  if (name == "noise_cov_a") return "Sigma_A, the covariance of the noise in a row of A (symmetric PSD). Needs 'NoiseCovB'.";
  return "Sigma_B, the covariance of the noise in a row of B (symmetric PSD).";
}

template <typename Request>
std::vector<MatlabOption> help_of(const std::vector<OptionSpec<Request>>& table, bool (*takes)(std::string_view)) {
  std::vector<MatlabOption> out;
  for (const OptionSpec<Request>& spec : table) {
    if (takes && !takes(spec.name)) continue;
    std::string help = spell_options(spec.help, Frontend::Matlab);
    if (matrix_option(spec.name)) help = matrix_help(spec.name);
    out.push_back({camel_case(spec.name), type_name(matlab_shape(spec.name, spec.type)), help,
                   std::string(spec.default_text)});
  }
  return out;
}

template <typename Request>
const OptionSpec<Request>& spec_named(const std::vector<OptionSpec<Request>>& table, std::string_view typed,
                                      bool (*takes)(std::string_view), std::string_view function) {
  std::string names;
  for (const OptionSpec<Request>& spec : table) {
    if (takes && !takes(spec.name)) continue;
    if (same_name(camel_case(spec.name), typed)) return spec;
    names += (names.empty() ? "" : ", ") + camel_case(spec.name);
  }
  throw OptionError("spdfit." + std::string(function) + " has no option '" + std::string(typed) + "' (its options: " +
                    names + ")");
}

// Sets each pair in `request` and returns the library names given (those not left at [] ).
template <typename Request>
std::vector<std::string_view> set_pairs(Request& request, const std::vector<OptionSpec<Request>>& table,
                                        const std::vector<NameValue>& pairs, bool (*takes)(std::string_view),
                                        std::string_view function) {
  std::vector<std::string_view> given;
  for (const NameValue& pair : pairs) {
    const OptionSpec<Request>& spec = spec_named(table, pair.name, takes, function);
    if (std::find(given.begin(), given.end(), spec.name) != given.end()) {
      throw OptionError("`" + std::string(spec.name) + "` is given twice");
    }
    if (pair.empty) {
      if (!spec.nullable) throw OptionError("`" + std::string(spec.name) + "` cannot be [] (it has no default to stand for)");
      continue;
    }
    if (pair.matrix.size() == 0) set_option(request, spec, pair.value);  // matrices: fit_options
    given.push_back(spec.name);
  }
  return given;
}

}  // namespace

ValueShape value_shape(OptionType type) {
  switch (type) {
    case OptionType::Flag:
    case OptionType::Boolean: return ValueShape::Boolean;
    case OptionType::Integer: return ValueShape::Integer;
    case OptionType::Real: return ValueShape::Real;
    case OptionType::Text: return ValueShape::Text;
    case OptionType::RealList:
    case OptionType::Vector: return ValueShape::List;
    case OptionType::Noise: return ValueShape::List;  // not offered (fit_takes)
  }
  return ValueShape::Real;
}

ValueShape matlab_shape(std::string_view name, OptionType type) {
  return matrix_option(name) ? ValueShape::Matrix : value_shape(type);
}

std::vector<MatlabOption> option_help(std::string_view function) {
  if (function == "fit") return help_of(fit_option_table(), &fit_takes);
  if (function == "identify") {
    std::vector<MatlabOption> out;
    for (const IdentifyOption& o : kIdentifyOptions) {
      out.push_back({camel_case(o.name), type_name(o.shape), std::string(o.help), ""});
    }
    for (MatlabOption& o : help_of(hexapod::physical_option_table(), nullptr)) {
      o.help += " (with 'Physical')";
      out.push_back(std::move(o));
    }
    for (MatlabOption& o : help_of(fit_option_table(), &fit_takes)) out.push_back(std::move(o));
    return out;
  }
  if (function == "nearest") return help_of(nearest_option_table(), nullptr);
  if (function == "payload.identify") {
    std::vector<MatlabOption> out;
    for (int k = 0; k < 8; ++k) out.push_back({camel_case(kPayloadSignals[k]), "matrix", kPayloadSignalHelp[k], ""});
    for (MatlabOption& o : help_of(payload::identify_option_table(), &payload_takes)) out.push_back(std::move(o));
    return out;
  }
  if (function == "physical.regress") {
    std::vector<MatlabOption> out = help_of(physical::regress_option_table(), &regress_takes);
    for (MatlabOption& o : out) {
      if (o.name == "NoiseCov") {
        o.type = "matrix";
        o.help = "The covariance of the noise in one sample's d outputs (d x d): the rows come in samples of d.";
      }
    }
    return out;
  }
  std::vector<MatlabOption> out;
  for (const SolveOption& o : kSolveOptions) {
    out.push_back({camel_case(o.name), "real", std::string(o.help), std::string(o.default_text)});
  }
  return out;
}

ValueShape option_shape(std::string_view function, std::string_view typed_name) {
  if (function == "identify") {
    if (const IdentifyOption* o = identify_option(typed_name)) return o->shape;
    if (const auto* spec = physical_option(typed_name)) return value_shape(spec->type);
    const OptionSpec<FitRequest>& spec = spec_named(fit_option_table(), typed_name, &fit_takes, "hexapod.identify");
    return matlab_shape(spec.name, spec.type);
  }
  if (function == "fit") {
    const OptionSpec<FitRequest>& spec = spec_named(fit_option_table(), typed_name, &fit_takes, function);
    return matlab_shape(spec.name, spec.type);
  }
  if (function == "nearest") return value_shape(spec_named(nearest_option_table(), typed_name, nullptr, function).type);
  if (function == "payload.identify") {
    if (payload_signal(typed_name) >= 0) return ValueShape::Matrix;
    return value_shape(spec_named(payload::identify_option_table(), typed_name, &payload_takes, function).type);
  }
  if (function == "physical.regress") {
    const auto& spec = spec_named(physical::regress_option_table(), typed_name, &regress_takes, function);
    return spec.name == "noise_cov" ? ValueShape::Matrix : value_shape(spec.type);
  }
  std::string names;
  for (const SolveOption& o : kSolveOptions) {
    if (same_name(camel_case(o.name), typed_name)) return ValueShape::Real;
    names += (names.empty() ? "" : ", ") + camel_case(o.name);
  }
  throw OptionError("spdfit.solve has no option '" + std::string(typed_name) + "' (its options: " + names + ")");
}

FitRequest fit_request(std::string_view method, const std::vector<NameValue>& pairs) {
  FitRequest request;
  const std::optional<Method> parsed = parse_method(method);
  if (!parsed) {
    std::string names;
    for (Method m : kSelectableMethods) names += (names.empty() ? "" : ", ") + std::string(to_string(m));
    throw OptionError("unknown method '" + std::string(method) + "' (methods: " + names + ")");
  }
  request.method = *parsed;
  const std::vector<std::string_view> given = set_pairs(request, fit_option_table(), pairs, &fit_takes, "fit");
  check_fit_request(request, given);
  return request;
}

FitOptions fit_options(const FitRequest& request, const std::vector<NameValue>& pairs, Eigen::Index n,
                       Eigen::Index d) {
  const Eigen::MatrixXd* matrices[4] = {nullptr, nullptr, nullptr, nullptr};  // rest_a, rest_b, cov_a, cov_b
  for (const NameValue& pair : pairs) {
    if (pair.matrix.size() == 0) continue;
    const std::string_view name = spec_named(fit_option_table(), pair.name, &fit_takes, "fit").name;
    const int slot = name == "rest_a" ? 0 : name == "rest_b" ? 1 : name == "noise_cov_a" ? 2 : 3;
    matrices[slot] = &pair.matrix;
  }
  if (matrices[0] && matrices[1]) {
    FitOptions options = request.options;
    options.noise = NoiseModel::from_rest(*matrices[0], *matrices[1]);
    return options;
  }
  if (matrices[2] && matrices[3]) {
    FitOptions options = request.options;
    options.noise = NoiseModel::from_cov(*matrices[2], *matrices[3]);
    return options;
  }
  return request.resolved_options(n, d);
}

IdentifyRequest identify_request(const std::vector<NameValue>& pairs) {
  IdentifyRequest out;
  std::vector<NameValue>& fit_pairs = out.fit_pairs;
  std::vector<std::string_view> physical_given;
  for (const NameValue& pair : pairs) {
    if (const IdentifyOption* o = identify_option(pair.name)) {
      if (pair.empty) continue;
      if (o->name == "physical") out.physical = std::get<bool>(pair.value);
      if (o->name == "geometry") out.geometry = std::get<std::string>(pair.value);
      if (o->name == "truth") out.truth = pair.matrix;
      if (o->name == "stiffness") out.stiffness = pair.matrix;
    } else if (const auto* spec = physical_option(pair.name)) {
      if (pair.empty) continue;
      set_option(out.physical_options, *spec, pair.value);
      physical_given.push_back(spec->name);
    } else {
      fit_pairs.push_back(pair);
    }
  }
  out.fit.method = Method::Auto;
  out.fit_given = set_pairs(out.fit, fit_option_table(), fit_pairs, &fit_takes, "hexapod.identify");
  // Every estimator runs: an option applies if it applies to one of them.
  check_option_combination(fit_option_table(), out.fit_given);
  check_option_combination(hexapod::physical_option_table(), physical_given);
  if (!physical_given.empty() && !out.physical) {
    throw OptionError("`" + std::string(physical_given.front()) + "` is an option of the physical fit: give `physical`, true");
  }
  if (!out.geometry.empty() && out.stiffness.size() > 0) {
    throw OptionError("give `geometry` or `stiffness`, not both (the geometry's strut stiffnesses give the modes)");
  }
  if (out.physical && out.geometry.empty()) {
    throw OptionError("`physical` needs `geometry`: the geometry file (spdfit hexapod model --write-geometry G.json)");
  }
  return out;
}

PayloadRequest payload_request(const std::vector<NameValue>& pairs) {
  PayloadRequest out;
  std::vector<NameValue> options;
  for (const NameValue& pair : pairs) {
    const int k = payload_signal(pair.name);
    if (k < 0) {
      options.push_back(pair);
      continue;
    }
    if (pair.empty) continue;
    payload::PayloadSignals& s = out.signals;
    Eigen::MatrixXd* targets[] = {&s.quaternion, &s.rotation, &s.gravity, &s.accel, &s.specific_force, &s.omega,
                                  &s.alpha, nullptr};
    if (targets[k]) {
      *targets[k] = pair.matrix;
    } else {
      s.time = Eigen::Map<const Eigen::VectorXd>(pair.matrix.data(), pair.matrix.size());
    }
  }
  const std::vector<std::string_view> given =
      set_pairs(out.request, payload::identify_option_table(), options, &payload_takes, "payload.identify");
  check_option_combination(payload::identify_option_table(), given);
  return out;
}

physical::RegressRequest regress_request(const std::vector<NameValue>& pairs) {
  physical::RegressRequest request;
  std::vector<NameValue> options;
  for (const NameValue& pair : pairs) {
    if (same_name(pair.name, "NoiseCov")) {
      if (!pair.empty) request.noise_cov = pair.matrix;
      continue;
    }
    options.push_back(pair);
  }
  const std::vector<std::string_view> given =
      set_pairs(request, physical::regress_option_table(), options, &regress_takes, "physical.regress");
  check_option_combination(physical::regress_option_table(), given);
  if (!request.prior_path.empty()) request.prior = read_rigid_bodies(request.prior_path);
  return request;
}

NearestRequest nearest_request(const std::vector<NameValue>& pairs) {
  NearestRequest request;
  const std::vector<std::string_view> given = set_pairs(request, nearest_option_table(), pairs, nullptr, "nearest");
  check_nearest_request(given);
  return request;
}

LinearSystemOptions solve_options(const std::vector<NameValue>& pairs) {
  LinearSystemOptions options;
  for (const NameValue& pair : pairs) {
    if (pair.empty) continue;
    const double value = std::get<double>(pair.value);
    const bool threshold = same_name(pair.name, "Threshold");
    const NumberRange range = threshold ? NumberRange{0.0, 1.0, false, true} : NumberRange{0.0, 1.0};
    if (!(std::abs(value) <= std::numeric_limits<double>::max()) || !range.contains(value)) {
      throw OptionError(std::string(threshold ? "`threshold`" : "`rcond_warning`") + " must be a " +
                        range.describe(false) + ", got " + value_text(value));
    }
    if (threshold) {
      options.rank_tolerance = value;
    } else {
      options.rcond_warning = value;
    }
  }
  return options;
}

}  // namespace spdfit::matlab
