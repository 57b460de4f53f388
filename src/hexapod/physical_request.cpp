// The physical fit's option table: each option declared once, with everything the front ends need.
#include "spdfit/hexapod/physical_request.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "physical/common_options.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/io.hpp"

namespace spdfit::hexapod {

namespace {

using Spec = OptionSpec<PhysicalOptions>;

std::vector<Spec> make_table() {
  std::vector<Spec> table;

  Spec struts;
  struts.name = "strut_masses";
  struts.cli = "--fit-strut-mass";
  struts.python = "fit_strut_mass";
  struts.type = OptionType::Choice;
  struts.choices = {"geometry", "common", "each"};
  struts.help =
      "Estimate the struts' moving masses too: one mass common to the six struts, or each strut's "
      "(only where the geometry identifies them; 'geometry' takes the geometry's, not estimated)";
  struts.default_text = "geometry";
  struts.set = [](PhysicalOptions& o, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const std::optional<StrutMasses> parsed = parse_strut_masses(name);
    if (!parsed) throw OptionError("`strut_masses` must be common, each or geometry, got '" + name + "'");
    o.strut_masses = *parsed;
  };
  struts.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> {
    return std::string(to_string(o.strut_masses));
  };
  table.push_back(struts);

  Spec criterion;
  criterion.name = "criterion";
  criterion.cli = "--physical-criterion";
  criterion.python = "criterion";
  criterion.type = OptionType::Choice;
  criterion.choices = {"eiv", "ls"};
  criterion.help =
      "The physical fit's criterion: errors in variables (eiv: noise in A and B, consistent as m "
      "grows) or least squares (ls: noise in B only, biased towards a lighter payload when A is noisy)";
  criterion.default_text = "eiv";
  criterion.set = [](PhysicalOptions& o, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const std::optional<PhysicalCriterion> parsed = parse_physical_criterion(name);
    if (!parsed) throw OptionError("`criterion` must be eiv or ls, got '" + name + "'");
    o.criterion = *parsed;
  };
  criterion.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> {
    return std::string(to_string(o.criterion));
  };
  table.push_back(criterion);

  Spec consistent;
  consistent.name = "consistent";
  consistent.python = "consistent";
  consistent.type = OptionType::Boolean;
  consistent.help =
      "Enforce physical consistency (the payload's pseudo-inertia positive semidefinite, strut "
      "masses non-negative); False is the unconstrained grey-box fit of the same model, which may "
      "return a payload that cannot exist";
  consistent.default_text = "True";
  consistent.nullable = false;
  consistent.excludes = {"unconstrained"};
  consistent.set = [](PhysicalOptions& o, const OptionValue& v) { o.consistent = std::get<bool>(v); };
  consistent.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> { return o.consistent; };
  table.push_back(consistent);

  Spec unconstrained;
  unconstrained.name = "unconstrained";
  unconstrained.cli = "--unconstrained";
  unconstrained.type = OptionType::Flag;
  unconstrained.help =
      "The physical fit without the consistency constraint: the grey-box fit of the same model, "
      "for comparison, which may return a payload that cannot exist";
  unconstrained.nullable = false;
  unconstrained.excludes = {"consistent"};
  unconstrained.set = [](PhysicalOptions& o, const OptionValue& v) {
    if (std::get<bool>(v)) o.consistent = false;
  };
  table.push_back(unconstrained);

  Spec offsets;
  offsets.name = "offsets";
  offsets.cli = "--offsets";
  offsets.python = "offsets";
  offsets.type = OptionType::Choice;
  offsets.value_name = "none|estimate|rest";
  offsets.choices = {"none", "estimate", "rest"};
  offsets.help = "Constant offsets in the data (a static load in untared forces, an accelerometer's bias): rest "
                 "subtracts the means of the rest rows (`rest_a` and `rest_b`) from A and B before the physical fit "
                 "(taring); estimate fits B ~= A M_p + 1 c^T (the data centred by their column means; c is "
                 "reported), for logs without rest rows; none fits the data as given, with a warning when the "
                 "forces look untared";
  offsets.default_text = "none";
  offsets.set = [](PhysicalOptions& o, const OptionValue& v) {
    o.tare = std::get<std::string>(v) == "rest";
    o.intercept = std::get<std::string>(v) == "estimate";
  };
  offsets.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> {
    return std::string(o.tare ? "rest" : o.intercept ? "estimate" : "none");
  };
  table.push_back(offsets);

  // The fit's robust options, spelled and checked as the fit table does, setting the physical fit's.
  Spec robust = spdfit::physical::detail::like_fit_option<PhysicalOptions>("robust");
  robust.help = "A robust physical fit: rows reweighted by their residual under the physical model, whitened by the "
                "noise covariances (an M-estimator); huber for gross errors in B, tukey (from least trimmed squares) "
                "also for wrong values in A. With `bootstrap`, each resample is reweighted from the estimate";
  robust.set = [](PhysicalOptions& o, const OptionValue& v) {
    o.robust = robust_loss_named(std::get<std::string>(v)).value_or(RobustLoss::None);  // a choice: named
  };
  robust.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> { return std::string(to_string(o.robust)); };
  table.push_back(robust);
  Spec tuning = spdfit::physical::detail::like_fit_option<PhysicalOptions>("robust_tuning");
  tuning.set = [](PhysicalOptions& o, const OptionValue& v) { o.robust_tuning = std::get<double>(v); };
  tuning.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> {
    if (!o.robust_tuning) return std::nullopt;
    return *o.robust_tuning;
  };
  table.push_back(tuning);

  Spec no_plausible;
  no_plausible.name = "no_plausibility_check";
  no_plausible.cli = "--no-plausibility-check";
  no_plausible.python = "no_plausibility_check";
  no_plausible.type = OptionType::Flag;
  no_plausible.help =
      "Fit data whose implied payload mass is not positive or more than a factor 100 from the geometry's, "
      "instead of refusing them (the geometry is in SI units: forces logged in kN are 1000 times too small)";
  no_plausible.nullable = false;
  no_plausible.set = [](PhysicalOptions& o, const OptionValue& v) { o.plausibility_check = !std::get<bool>(v); };
  no_plausible.get = [](const PhysicalOptions& o) -> std::optional<OptionValue> { return !o.plausibility_check; };
  table.push_back(no_plausible);

  return table;
}

}  // namespace

const std::vector<OptionSpec<PhysicalOptions>>& physical_option_table() {
  static const std::vector<OptionSpec<PhysicalOptions>> table = make_table();
  return table;
}

void apply_fit_options(const FitOptions& fit, const std::vector<std::string_view>& given,
                       PhysicalOptions& options) {
  options.bootstrap = fit.bootstrap;
  options.confidence = fit.confidence;
  options.seed = fit.seed;
  options.threads = fit.threads;
  for (std::string_view name : given) {
    if (name == "max_iterations") options.max_iterations = fit.max_iterations;
    if (name == "rank_tolerance") options.rank_tolerance = fit.rank_tolerance;
  }
  if (fit.noise) {
    // The physical fit is of the six struts: standard deviations per side become 6 x 6.
    const NoiseModel model = fit.noise->resolved(6, 6);
    options.noise_cov_a = model.cov_a();
    options.noise_cov_b = model.cov_b();
    if (model.rest_rows()) {
      options.rest_mean_a = model.rest_mean_a();
      options.rest_mean_b = model.rest_mean_b();
      options.rest_rows = *model.rest_rows();
    }
  }
}

namespace {

using FitSpec = OptionSpec<PhysicalRequest>;

std::vector<FitSpec> make_fit_table() {
  std::vector<FitSpec> table;
  const auto positional = [&table](std::string_view name, std::string_view python, OptionType type,
                                   std::string_view help, std::function<void(PhysicalRequest&, const OptionValue&)> set) {
    FitSpec spec;
    spec.name = name;
    spec.python = python;
    spec.type = type;
    spec.help = help;
    spec.positional = true;
    spec.required = true;
    spec.set = std::move(set);
    table.push_back(std::move(spec));
  };
  positional("a", "A", OptionType::Matrix, "Accelerations along the struts (m x 6)",
             [](PhysicalRequest& r, const OptionValue& v) { r.a = std::get<MatrixInput>(v); });
  positional("b", "B", OptionType::Matrix, "Base forces (m x 6)",
             [](PhysicalRequest& r, const OptionValue& v) { r.b = std::get<MatrixInput>(v); });
  positional("geometry", "geometry", OptionType::Geometry, "The hexapod's geometry: the Jacobian and nominal payload",
             [](PhysicalRequest& r, const OptionValue& v) { r.geometry = std::get<GeometryInput>(v); });
  for (FitSpec& spec : lifted_options(physical_option_table(), &PhysicalRequest::options)) table.push_back(std::move(spec));
  for (FitSpec& spec : lifted_options(fit_option_table(), &PhysicalRequest::fit,
                                      {"rank_tolerance", "noise_cov_a", "noise_cov_b", "max_iterations", "bootstrap",
                                       "confidence", "seed", "threads"})) {
    // Given, the iteration limit and the rank cut-off are the physical fit's own (its default
    // iteration limit is 500: its barrier path takes more Newton steps than the fit's 200).
    if (spec.name == "max_iterations") {
      spec.default_text = "500";
      spec.set = [set = spec.set](PhysicalRequest& r, const OptionValue& v) {
        set(r, v);
        r.options.max_iterations = r.fit.options.max_iterations;
      };
      spec.get = [](const PhysicalRequest& r) -> std::optional<OptionValue> {
        return std::int64_t{r.options.max_iterations};
      };
    } else if (spec.name == "rank_tolerance") {
      spec.set = [set = spec.set](PhysicalRequest& r, const OptionValue& v) {
        set(r, v);
        r.options.rank_tolerance = r.fit.options.rank_tolerance;
      };
    } else if (spec.name == "noise_cov_a" || spec.name == "noise_cov_b") {
      spec.python = spec.name;
      spec.help = spec.name == "noise_cov_a" ? "Sigma_A, the 6 x 6 covariance of the noise in a row of A (default: "
                                               "identity, equal noise in A and B)"
                                             : "Sigma_B, the 6 x 6 covariance of the noise in a row of B";
    }
    table.push_back(std::move(spec));
  }
  return trimmed_rules(std::move(table));
}

}  // namespace

const std::vector<OptionSpec<PhysicalRequest>>& physical_fit_table() {
  static const std::vector<OptionSpec<PhysicalRequest>> table = make_fit_table();
  return table;
}

void check_physical_request(const PhysicalRequest& request, const std::vector<std::string_view>& given) {
  check_option_combination(physical_fit_table(), given);
  if (!request.geometry.given()) {
    throw OptionError("the physical fit needs `geometry`: the Jacobian and the nominal payload come from it",
                      Code::Argument, "geometry");
  }
}

PhysicalEstimate run_physical(const PhysicalRequest& request) {
  const auto values = [&request](const MatrixInput& m) {
    return m.from_file() ? io::read_matrix(m.path, request.fit.read) : m.values;
  };
  const Geometry geometry = request.geometry.value ? *request.geometry.value : read_geometry(request.geometry.path);
  PhysicalOptions options = request.options;
  apply_fit_options(request.fit.resolved_options(6, 6), {}, options);
  return identify_physical(values(request.a), values(request.b), geometry, options);
}

}  // namespace spdfit::hexapod
