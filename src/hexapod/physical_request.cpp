// The physical fit's option table: each option declared once, with everything the front ends need.
#include "spdfit/hexapod/physical_request.hpp"

#include <cstdint>
#include <string>

namespace spdfit::hexapod {

namespace {

using Spec = OptionSpec<PhysicalOptions>;

std::vector<Spec> make_table() {
  std::vector<Spec> table;

  Spec struts;
  struts.name = "strut_masses";
  struts.cli = "--fit-strut-mass";
  struts.python = "fit_strut_mass";
  struts.type = OptionType::Text;
  struts.value_name = "common|each";
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
  criterion.type = OptionType::Text;
  criterion.value_name = "eiv|ls";
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
  unconstrained.set = [](PhysicalOptions& o, const OptionValue& v) {
    if (std::get<bool>(v)) o.consistent = false;
  };
  table.push_back(unconstrained);

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
  }
}

}  // namespace spdfit::hexapod
