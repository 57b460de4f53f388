// `hexapod identify` as one workflow: its option table, its rules, its run.
#include "spdfit/hexapod/identify_request.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>
#include <utility>

#include "spdfit/fit_files.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"
#include "interface/matrix_inputs.hpp"
#include "pipeline/sentinels.hpp"
#include "pipeline/log_rows.hpp"
#include "pipeline/offsets.hpp"
#include "pipeline/units.hpp"

namespace spdfit::hexapod {

namespace {

// Data in other units than the geometry's SI give themselves away by the estimates' scale: one
// warning (not one per method) when the median of the estimates' traces is more than a factor
// kPlausibleFactor from the trace of the geometry's M_p, naming the factor the units are off by.
std::optional<Warning> units_warning(const std::vector<MethodIdentification>& methods, const Eigen::MatrixXd& nominal) {
  constexpr double kPlausibleFactor = 100.0;
  const double reference = nominal.trace();
  if (!(reference > 0.0) || !std::isfinite(reference)) return std::nullopt;
  std::vector<double> traces;
  for (const MethodIdentification& m : methods) {
    if (m.result.ok() && std::isfinite(m.result.X.trace())) traces.push_back(m.result.X.trace());
  }
  if (traces.empty()) return std::nullopt;
  std::sort(traces.begin(), traces.end());
  const std::size_t k = traces.size();
  const double median = k % 2 == 1 ? traces[k / 2] : 0.5 * (traces[k / 2 - 1] + traces[k / 2]);
  const double ratio = median / reference;
  if (ratio >= 1.0 / kPlausibleFactor && ratio <= kPlausibleFactor) return std::nullopt;
  std::string how = "not positive, unlike";
  std::string fix = "check the data's units, signs and strut order against the geometry's";
  if (ratio > 0.0) {
    how = format_number(ratio > 1.0 ? ratio : 1.0 / ratio) + " times " + (ratio > 1.0 ? "above" : "below");
    const double decade = std::pow(10.0, std::round(std::log10(1.0 / ratio)));
    const std::string f = decade >= 1.0 ? std::to_string(std::llround(decade)) : format_number(decade);
    fix = "multiply the forces by " + f + " (`scale_b` " + f + "; or the accelerations by its inverse, `scale_a`)";
  }
  const std::string range = traces.front() == traces.back()
                                ? format_number(median)
                                : format_number(traces.front()) + " to " + format_number(traces.back()) + " (median " +
                                      format_number(median) + ")";
  return Warning(Code::PhysicalNotice,
                 "the estimates' traces are " + range + ", " + how + " the geometry's M_p (" + format_number(reference) +
                     " kg): the geometry is in SI units, and the data are probably in others (forces in kN?): " + fix,
                 "geometry");
}

// Each method's warnings, after its name ("spde: ..."), each fact once: a warning that several
// methods give alike (the same code and text, the method's own name at its start aside: a notice
// about the data or the noise model) is one warning after all their names ("ls, procrustes,
// psd-ls: each models noise in B only ..."; "every estimator: ..." when all give it).
void add_method_warnings(const std::vector<MethodIdentification>& methods, std::vector<Warning>& out) {
  struct Group {
    Code code;
    std::string key, subject;
    bool named = false;
    std::vector<std::string> names;
  };
  std::vector<Group> groups;
  for (const MethodIdentification& m : methods) {
    const std::string name(to_string(m.result.method));
    for (const Warning& w : m.result.warnings) {
      const bool named = w.text.rfind(name + " ", 0) == 0;
      const std::string key = named ? w.text.substr(name.size() + 1) : w.text;
      auto same = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
        return g.code == w.code && g.named == named && g.key == key;
      });
      if (same == groups.end()) {
        groups.push_back(Group{w.code, key, w.subject, named, {name}});
      } else {
        same->names.push_back(name);
      }
    }
  }
  for (Group& g : groups) {
    std::string names;
    for (const std::string& name : g.names) names += (names.empty() ? "" : ", ") + name;
    if (g.names.size() > 1 && g.names.size() == methods.size()) names = "every estimator";
    const std::string text = g.names.size() == 1 ? names + ": " + (g.named ? names + " " : std::string()) + g.key
                                                 : names + ": " + (g.named ? "each " : "") + g.key;
    out.emplace_back(g.code, text, g.subject);
  }
}

using Spec = OptionSpec<IdentifyRequest>;

// The fit's options every estimator of identify shares.
const std::vector<std::string_view> kSharedFitOptions = {
    "rank_tolerance", "noise_ratio", "noise", "rest_a", "rest_b", "noise_std_a", "noise_std_b", "noise_cov_a",
    "noise_cov_b", "max_iterations", "min_eig", "bootstrap", "confidence", "interval", "seed", "threads", "a_cols", "b_cols",
    "scale_a", "scale_b", "rows", "rest_rows", "time_col", "offsets", "robust", "robust_tuning"};

const MatrixInput& matrix(const OptionValue& v) { return std::get<MatrixInput>(v); }

std::vector<Spec> make_table() {
  std::vector<Spec> table;

  Spec a;
  a.name = "a";
  a.cli = "A";
  a.python = "A";
  a.type = OptionType::Matrix;
  a.help = "The payload's accelerations along the struts (m x 6)";
  a.positional = true;
  a.required = true;
  a.set = [](IdentifyRequest& r, const OptionValue& v) { r.a = matrix(v); };
  table.push_back(a);

  Spec b;
  b.name = "b";
  b.cli = "B";
  b.python = "B";
  b.type = OptionType::Matrix;
  b.help = "The base forces (m x 6). Without it, `a_cols` and `b_cols` choose the columns of the accelerations "
           "and the forces in A's file";
  b.positional = true;
  b.set = [](IdentifyRequest& r, const OptionValue& v) { r.b = matrix(v); };
  table.push_back(b);

  Spec truth;
  truth.name = "truth";
  truth.cli = "--truth";
  truth.python = "truth";
  truth.type = OptionType::Matrix;
  truth.value_name = "FILE";
  truth.help = "The true M_p (n x n), to report each method's error";
  truth.set = [](IdentifyRequest& r, const OptionValue& v) { r.truth = matrix(v); };
  table.push_back(truth);

  Spec geometry;
  geometry.name = "geometry";
  geometry.cli = "--geometry";
  geometry.python = "geometry";
  geometry.type = OptionType::Geometry;
  geometry.value_name = "FILE";
  geometry.help = "The hexapod's geometry (spdfit hexapod model --write-geometry G.json): its strut stiffness "
                  "gives the modes, and the physical fit its Jacobian and nominal payload";
  geometry.excludes = {"stiffness"};
  geometry.set = [](IdentifyRequest& r, const OptionValue& v) { r.geometry = std::get<GeometryInput>(v); };
  table.push_back(geometry);

  Spec stiffness;
  stiffness.name = "stiffness";
  stiffness.cli = "--stiffness";
  stiffness.python = "stiffness";
  stiffness.type = OptionType::Matrix;
  stiffness.value_name = "K";
  stiffness.help = "Strut stiffness (N/m) for the modes: one number for every strut, one per strut, or the n x n "
                   "matrix K (on the command line comma-separated numbers, or a file)";
  stiffness.excludes = {"geometry"};
  stiffness.set = [](IdentifyRequest& r, const OptionValue& v) { r.stiffness = matrix(v); };
  table.push_back(stiffness);

  Spec physical;
  physical.name = "physical";
  physical.cli = "--physical";
  physical.python = "physical";
  physical.type = OptionType::Flag;
  physical.help = "Also fit the payload's mass, centre of mass and inertia (physically consistent) with the "
                  "Jacobian of `geometry` known, each beside the geometry's nominal value";
  physical.default_text = "false";
  physical.nullable = false;
  physical.needs = {"geometry"};
  physical.needs_message =
      "`physical` needs `geometry`: the Jacobian and the nominal payload come from the geometry file";
  physical.set = [](IdentifyRequest& r, const OptionValue& v) { r.physical = std::get<bool>(v); };
  physical.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return r.physical; };
  table.push_back(physical);

  for (Spec& spec : lifted_options(physical_option_table(), &IdentifyRequest::physical_options)) {
    // The fit's `offsets` and `robust` (below) set the physical fit's too: one option for every estimator.
    if (spec.name == "offsets" || spec.name == "robust" || spec.name == "robust_tuning") continue;
    spec.needs = {"physical"};
    table.push_back(std::move(spec));
  }
  Spec urdf;
  urdf.name = "urdf";
  urdf.cli = "--urdf";
  urdf.type = OptionType::File;
  urdf.value_name = "FILE";
  urdf.help = "With `physical`: also write the payload as a URDF <link> with its <inertial> to FILE";
  urdf.needs = {"physical"};
  urdf.needs_message = "`urdf` needs `physical`: it writes the payload's physical fit";
  urdf.set = [](IdentifyRequest& r, const OptionValue& v) { r.urdf = std::get<std::string>(v); };
  table.push_back(urdf);
  Spec precision;
  precision.name = "precision";
  precision.cli = "--precision";
  precision.type = OptionType::Integer;
  precision.value_name = "N";
  precision.help = "Significant digits of `urdf`'s numbers";
  precision.default_text = "9";
  precision.range = {1.0, 17.0};
  precision.needs = {"urdf"};
  precision.set = [](IdentifyRequest& r, const OptionValue& v) { r.precision = int(std::get<std::int64_t>(v)); };
  precision.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.precision}; };
  table.push_back(precision);

  for (Spec& spec : lifted_options(fit_option_table(), &IdentifyRequest::fit, kSharedFitOptions)) {
    // The iteration limit and the rank cut-off, given, hold for the physical fit too (whose
    // default iteration limit is its own: its barrier path takes more Newton steps).
    if (spec.name == "max_iterations") {
      spec.set = [set = spec.set](IdentifyRequest& r, const OptionValue& v) {
        set(r, v);
        r.physical_options.max_iterations = r.fit.options.max_iterations;
      };
    } else if (spec.name == "offsets") {
      spec.help = "Constant offsets in the columns of A and B (a static load in untared forces, an "
                  "accelerometer's bias): estimate fits A X + 1 c^T ~= B (the data centred by their column "
                  "means), rest subtracts the means of the rows recorded at rest (those the noise model is made "
                  "from), for every estimator and `physical`; none takes the data as given";
      spec.set = [set = spec.set](IdentifyRequest& r, const OptionValue& v) {
        set(r, v);
        r.physical_options.tare = r.fit.options.offsets == Offsets::Rest;
        r.physical_options.intercept = r.fit.options.offsets == Offsets::Estimate;
      };
    } else if (spec.name == "robust") {
      spec.help = "A robust fit: rows reweighted by their residual, whitened by the noise model (an M-estimator), "
                  "for every estimator but spde and for `physical`: huber for gross errors in B, tukey (from least "
                  "trimmed squares) also for wrong values in A; with `bootstrap`, each resample refitted robustly";
      spec.set = [set = spec.set](IdentifyRequest& r, const OptionValue& v) {
        set(r, v);
        r.physical_options.robust = r.fit.options.robust;
      };
    } else if (spec.name == "robust_tuning") {
      spec.set = [set = spec.set](IdentifyRequest& r, const OptionValue& v) {
        set(r, v);
        r.physical_options.robust_tuning = r.fit.options.robust_tuning;
      };
    } else if (spec.name == "rank_tolerance") {
      spec.set = [set = spec.set](IdentifyRequest& r, const OptionValue& v) {
        set(r, v);
        r.physical_options.rank_tolerance = r.fit.options.rank_tolerance;
      };
    }
    table.push_back(std::move(spec));
  }
  for (Spec& spec : output_options(&IdentifyRequest::output, {"json", "output"}, {"Print every result as JSON"})) {
    table.push_back(std::move(spec));
  }
  table = trimmed_rules(std::move(table));
  for (Spec& spec : table) {
    if (spec.name == "threads") spec.needs_message = "`threads` applies to the bootstrap: give `bootstrap` N as well";
  }
  return table;
}

// The stiffness matrix K for n struts from one number, n numbers or n x n (InputError naming it).
Eigen::MatrixXd stiffness_matrix(const Eigen::MatrixXd& K, Eigen::Index n) {
  const auto fail = [&](const std::string& problem) -> Eigen::MatrixXd {
    throw InputError("`stiffness` " + problem, Code::DataShape, "stiffness");
  };
  if (!K.allFinite() || ((K.array() < 0.0).any() && (K.rows() == 1 || K.cols() == 1))) {
    return fail("must be finite numbers >= 0 (N/m)");
  }
  if (K.size() == 1) return Eigen::MatrixXd::Identity(n, n) * K(0, 0);
  if ((K.rows() == 1 || K.cols() == 1) && K.size() == n) {
    return Eigen::Map<const Eigen::VectorXd>(K.data(), n).asDiagonal();
  }
  if (K.rows() == n && K.cols() == n) return K;
  return fail("is " + std::to_string(K.rows()) + "x" + std::to_string(K.cols()) + ": give one number, " +
              std::to_string(n) + " (one per strut) or the " + std::to_string(n) + "x" + std::to_string(n) +
              " matrix");
}

}  // namespace

const std::vector<OptionSpec<IdentifyRequest>>& identify_option_table() {
  static const std::vector<OptionSpec<IdentifyRequest>> table = make_table();
  return table;
}

void check_identify_request(const IdentifyRequest& request, const std::vector<std::string_view>& given) {
  check_option_combination(identify_option_table(), given);
  spdfit::detail::check_b_given(request.b.given(), request.fit.a_cols, request.fit.b_cols);
  if (!request.a.from_file() && (!request.fit.a_cols.empty() || !request.fit.b_cols.empty())) {
    throw OptionError("`a_cols` and `b_cols` choose columns of a file, but A was given as values",
                      Code::OptionNotApplicable, "a_cols");
  }
}

std::optional<Problem> Identification::failure() const {
  if (!physical || physical->ok()) return std::nullopt;
  return Problem{Code::NumericalFailure, "the physical fit failed: " + physical->message, "physical"};
}

Identification run_identify(const IdentifyRequest& request) {
  Identification out;
  const io::ReadOptions& read = request.fit.read;
  Eigen::MatrixXd A, B;
  std::string b_name;  // the file named in a size problem of B
  if (request.a.from_file()) {
    const std::string b_path = request.b.from_file() ? request.b.path : std::string();
    DataPair data = read_pair(request.a.path, b_path, data_read_options(request.fit, b_path));
    A = std::move(data.A);
    B = std::move(data.B);
    out.warnings = std::move(data.warnings);
    out.a_columns = std::move(data.a_columns);
    out.b_columns = std::move(data.b_columns);
    b_name = b_path.empty() ? request.a.path : b_path;
  } else {
    A = request.a.values;
    B = spdfit::detail::values_of(request.b, read, out.warnings);
  }
  const Eigen::Index n = A.cols();
  if (B.cols() != n) {
    const std::string problem = "B has " + std::to_string(B.cols()) + " columns but A" +
                                (request.a.from_file() ? " (" + request.a.path + ")" : std::string()) + " has " +
                                std::to_string(n) +
                                ": the mass-inertia matrix is square, so forces and accelerations need the same "
                                "struts";
    if (!b_name.empty()) throw io::DataError(b_name, 0, 0, problem, Code::DataShape);
    throw InputError(problem, Code::DataShape, "b");
  }
  if (request.truth) {
    Eigen::MatrixXd truth = spdfit::detail::values_of(*request.truth, read, out.warnings);
    if (truth.rows() != n || truth.cols() != n) {
      spdfit::detail::shape_problem(*request.truth, "truth", "the true M_p must be " + std::to_string(n) + "x" + std::to_string(n));
    }
    out.options.truth = std::move(truth);
  }
  if (request.geometry.given()) {
    out.geometry = request.geometry.value ? *request.geometry.value : read_geometry(request.geometry.path);
    if (n != 6) {
      const std::string problem = "a hexapod geometry needs data with 6 columns (struts)";
      if (request.a.from_file()) throw io::DataError(request.a.path, 0, 0, problem, Code::DataShape);
      throw InputError(problem + "; A has " + std::to_string(n), Code::DataShape, "a");
    }
    out.options.stiffness = Eigen::MatrixXd(out.geometry->strut_stiffness.asDiagonal());
  } else if (request.stiffness) {
    const Eigen::MatrixXd K = spdfit::detail::values_of(*request.stiffness, read, out.warnings);
    try {
      out.options.stiffness = stiffness_matrix(K, n);
    } catch (const InputError& e) {
      // Numbers typed as the option's value are the option's problem; a file's, the data's.
      if (!request.stiffness->from_file()) throw OptionError(e.what(), Code::OptionValue, "stiffness");
      spdfit::detail::shape_problem(*request.stiffness, "stiffness", e.what());
    }
  }
  // One log: the rows fitted and the rest segment (a noise model) from the data themselves.
  out.options.fit = request.fit.resolved_options(n, n);
  spdfit::detail::RowNumbers numbers;
  const std::vector<Warning> found = spdfit::detail::apply_log_rows(
      request.fit, A, B, request.a.from_file() ? request.a.path : "A", out.options.fit, &numbers);
  out.warnings.insert(out.warnings.end(), found.begin(), found.end());
  if (std::optional<Warning> w = spdfit::detail::sentinel_warning(A, B, numbers)) out.warnings.push_back(std::move(*w));
  // Data in other units: A and B multiplied as read, the noise model (the files' units) with them.
  if (const std::optional<spdfit::detail::Units> units = spdfit::detail::units_of(out.options.fit, n, n)) {
    spdfit::detail::apply_units(*units, A, B);
    out.options.fit = spdfit::detail::options_in_units(out.options.fit, *units);
  }
  // Offsets a fit without them would take for signal: said once for every estimator.
  // (Untared forces with `physical`: its fit says so itself, in the physical model's words.)
  const std::vector<Warning> offset_notes =
      spdfit::detail::offset_warnings(A, B, nullptr, out.options.fit, !request.physical);
  out.warnings.insert(out.warnings.end(), offset_notes.begin(), offset_notes.end());
  // Rows that dominate the fit: said once, as auto's fit finds them.
  if (std::optional<Warning> w = spdfit::detail::dominant_rows_check(A, B, Method::Auto, out.options.fit, numbers)) {
    out.warnings.push_back(std::move(*w));
  }
  out.methods = identify(A, B, out.options);
  for (MethodIdentification& m : out.methods) {  // robust fits' rows numbered as in the file
    if (m.result.robust) spdfit::detail::number_rows(*m.result.robust, numbers);
  }
  if (out.geometry) {
    if (std::optional<Warning> w = units_warning(out.methods, joint_space_mass_matrix(*out.geometry))) {
      out.warnings.push_back(std::move(*w));
    }
  }
  add_method_warnings(out.methods, out.warnings);
  if (!request.physical) return out;
  // The bootstrap's options and the noise model, as every estimator had them (the iteration limit
  // and the rank cut-off were set for both by their options).
  PhysicalOptions physical_options = request.physical_options;
  apply_fit_options(out.options.fit, {}, physical_options);
  out.physical = identify_physical(A, B, *out.geometry, physical_options);
  if (out.physical->robust) spdfit::detail::number_rows(*out.physical->robust, numbers);  // as in the file
  for (const Warning& w : out.physical->warnings) out.warnings.emplace_back(w.code, "physical: " + w.text, w.subject);
  return out;
}

std::string urdf_text(const Identification& identification, const IdentifyRequest& request) {
  if (!identification.physical || !identification.physical->ok()) {
    throw InputError("`urdf` needs a successful physical fit: the payload was not identified", Code::PhysicalData,
                     "urdf");
  }
  return urdf_link(identification.physical->payload, "payload", request.precision);
}

std::string to_json(const Identification& identification) {
  if (identification.physical) return to_json(identification.methods, identification.options, *identification.physical);
  return to_json(identification.methods, identification.options);
}

std::string report(const Identification& identification) {
  if (identification.physical) {
    return report(identification.methods, identification.options, *identification.physical, *identification.geometry);
  }
  return report(identification.methods, identification.options);
}

}  // namespace spdfit::hexapod
