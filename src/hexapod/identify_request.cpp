// `hexapod identify` as one workflow: its option table, its rules, its run.
#include "spdfit/hexapod/identify_request.hpp"

#include <string>
#include <utility>

#include "spdfit/fit_files.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/io.hpp"

namespace spdfit::hexapod {

namespace {

using Spec = OptionSpec<IdentifyRequest>;

// The fit's options every estimator of identify shares.
const std::vector<std::string_view> kSharedFitOptions = {
    "rank_tolerance", "noise_ratio", "noise", "rest_a", "rest_b", "noise_std_a", "noise_std_b", "noise_cov_a",
    "noise_cov_b", "max_iterations", "min_eig", "bootstrap", "confidence", "seed", "threads", "a_cols", "b_cols"};

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
    spec.needs = {"physical"};
    table.push_back(std::move(spec));
  }
  for (Spec& spec : lifted_options(fit_option_table(), &IdentifyRequest::fit, kSharedFitOptions)) {
    // The iteration limit and the rank cut-off, given, hold for the physical fit too (whose
    // default iteration limit is its own: its barrier path takes more Newton steps).
    if (spec.name == "max_iterations") {
      spec.set = [set = spec.set](IdentifyRequest& r, const OptionValue& v) {
        set(r, v);
        r.physical_options.max_iterations = r.fit.options.max_iterations;
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
  if (!K.allFinite() || (K.array() < 0.0).any() && (K.rows() == 1 || K.cols() == 1)) {
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

// A matrix option's values: its file read (io::DataError naming it) or the values given.
Eigen::MatrixXd values_of(const MatrixInput& input, const io::ReadOptions& read, std::vector<Warning>& warnings) {
  if (!input.from_file()) return input.values;
  io::Table table = io::read_table(input.path, read);
  warnings.insert(warnings.end(), table.warnings.begin(), table.warnings.end());
  return std::move(table.values);
}

// A size problem of option `option`, named by its file when it came from one.
[[noreturn]] void size_problem(const MatrixInput& input, const std::string& option, const std::string& problem) {
  if (input.from_file()) throw io::DataError(input.path, 0, 0, problem, Code::DataShape);
  throw InputError(problem, Code::DataShape, option);
}

}  // namespace

const std::vector<OptionSpec<IdentifyRequest>>& identify_option_table() {
  static const std::vector<OptionSpec<IdentifyRequest>> table = make_table();
  return table;
}

void check_identify_request(const IdentifyRequest& request, const std::vector<std::string_view>& given) {
  check_option_combination(identify_option_table(), given);
  if (!request.b.given() && request.fit.a_cols.empty() && request.fit.b_cols.empty()) {
    throw OptionError("B's file is missing: give the files of A and B, or one file with `a_cols` and `b_cols` "
                      "choosing their columns",
                      Code::Argument, "b");
  }
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
    B = values_of(request.b, read, out.warnings);
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
    Eigen::MatrixXd truth = values_of(*request.truth, read, out.warnings);
    if (truth.rows() != n || truth.cols() != n) {
      size_problem(*request.truth, "truth", "the true M_p must be " + std::to_string(n) + "x" + std::to_string(n));
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
    const Eigen::MatrixXd K = values_of(*request.stiffness, read, out.warnings);
    try {
      out.options.stiffness = stiffness_matrix(K, n);
    } catch (const InputError& e) {
      // Numbers typed as the option's value are the option's problem; a file's, the data's.
      if (!request.stiffness->from_file()) throw OptionError(e.what(), Code::OptionValue, "stiffness");
      size_problem(*request.stiffness, "stiffness", e.what());
    }
  }
  out.options.fit = request.fit.resolved_options(n, n);
  out.methods = identify(A, B, out.options);
  for (const MethodIdentification& m : out.methods) {
    for (const Warning& w : m.result.warnings) {
      out.warnings.emplace_back(w.code, std::string(to_string(m.result.method)) + ": " + w.text, w.subject);
    }
  }
  if (!request.physical) return out;
  // The bootstrap's options and the noise model, as every estimator had them (the iteration limit
  // and the rank cut-off were set for both by their options).
  PhysicalOptions physical_options = request.physical_options;
  apply_fit_options(out.options.fit, {}, physical_options);
  out.physical = identify_physical(A, B, *out.geometry, physical_options);
  for (const Warning& w : out.physical->warnings) out.warnings.emplace_back(w.code, "physical: " + w.text, w.subject);
  return out;
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
