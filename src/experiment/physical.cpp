#include "spdfit/experiment/physical.hpp"

#include <algorithm>
#include <limits>
#include <set>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "spdfit/hexapod/model.hpp"

namespace spdfit::experiment {

namespace {

const PhysicalVariant kVariants[] = {
    {"physical", hexapod::PhysicalCriterion::ErrorsInVariables, true, hexapod::StrutMasses::Geometry},
    {"physical-ls", hexapod::PhysicalCriterion::LeastSquares, true, hexapod::StrutMasses::Geometry},
    {"grey-box-tls", hexapod::PhysicalCriterion::ErrorsInVariables, false, hexapod::StrutMasses::Geometry},
    {"grey-box-ls", hexapod::PhysicalCriterion::LeastSquares, false, hexapod::StrutMasses::Geometry},
};

}  // namespace

std::optional<PhysicalVariant> physical_variant(std::string_view name) {
  std::string_view base = name;
  std::optional<hexapod::StrutMasses> struts = hexapod::StrutMasses::Geometry;
  if (const std::size_t colon = name.find(':'); colon != std::string_view::npos) {
    base = name.substr(0, colon);
    struts = hexapod::parse_strut_masses(name.substr(colon + 1));
    if (!struts || *struts == hexapod::StrutMasses::Geometry) return std::nullopt;
  }
  for (const PhysicalVariant& v : kVariants) {
    if (v.name == base) {
      PhysicalVariant out = v;
      out.name = std::string(name);
      out.strut_masses = *struts;
      return out;
    }
  }
  return std::nullopt;
}

std::vector<std::string> physical_variant_names() {
  std::vector<std::string> out;
  for (const PhysicalVariant& v : kVariants) out.push_back(v.name);
  return out;
}

bool PhysicalExperimentOptions::is_valid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (samples.empty()) return fail("`samples` must list at least one number of samples");
  for (Eigen::Index m : samples) {
    if (m < 6) return fail("every number of `samples` must be at least 6 (M_p is 6 x 6), not " + std::to_string(m));
  }
  if (methods.empty() && variants.empty()) return fail("no methods to run");
  if (std::set<Method>(methods.begin(), methods.end()).size() != methods.size()) {
    return fail("`methods` lists a method twice");
  }
  if (std::set<std::string>(variants.begin(), variants.end()).size() != variants.size()) {
    return fail("`methods` lists a physical variant twice");
  }
  for (const std::string& name : variants) {
    if (!physical_variant(name)) {
      std::string names;
      for (const std::string& n : physical_variant_names()) names += (names.empty() ? "" : ", ") + n;
      return fail("unknown physical variant '" + name + "' (the variants are " + names +
                  ", with :common or :each to estimate the strut masses)");
    }
  }
  std::string why;
  if (!simulation.is_valid(&why)) return fail(why);
  if (geometry && !geometry->is_valid(&why)) return fail("invalid hexapod geometry: " + why);
  if (payload && !is_well_formed(*payload, &why)) return fail("invalid payload: " + why);
  return true;
}

PhysicalExperimentResult run_physical_experiment(const PhysicalExperimentOptions& options,
                                                 const MonteCarloOptions& monte_carlo) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("physical experiment: " + error);
  PhysicalExperimentResult result;
  result.options = options;
  const hexapod::Geometry geometry = options.geometry ? *options.geometry : hexapod::cubic_geometry();
  const RigidBodyInertia payload = options.payload ? *options.payload : hexapod::nominal_payload(geometry);
  result.truth = hexapod::joint_space_mass_matrix(geometry, payload);
  result.trials = monte_carlo.trials;
  result.seed = monte_carlo.seed;

  std::vector<PhysicalVariant> variants;
  for (const std::string& name : options.variants) variants.push_back(*physical_variant(name));
  for (const PhysicalVariant& v : variants) {
    if (v.strut_masses != hexapod::StrutMasses::Geometry) {
      const hexapod::PhysicalDesign design = hexapod::physical_design(geometry, v.strut_masses);
      if (design.rank < design.parameters) {
        throw std::invalid_argument("physical experiment: " + v.name + " cannot estimate the strut masses on this geometry: " +
                                    design.confounded);
      }
    }
  }
  const std::size_t generic = options.methods.size(), count = generic + variants.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();

  for (Eigen::Index m : options.samples) {
    hexapod::SimulationOptions simulation = options.simulation;
    simulation.samples = m;
    std::vector<std::vector<double>> errors(count, std::vector<double>(monte_carlo.trials, nan));
    std::vector<std::vector<char>> inconsistent(count, std::vector<char>(monte_carlo.trials, 0));
    run_trials(monte_carlo, [&](std::size_t k, Random& random) {
      thread_local hexapod::Measurements data;
      thread_local std::vector<Eigen::MatrixXd> X;
      hexapod::simulate_into(result.truth, simulation, random, data);
      if (generic > 0) estimate(data.A, data.B, options.methods, X);
      for (std::size_t i = 0; i < generic; ++i) {
        if (X[i].size() == 0) continue;
        errors[i][k] = (X[i] - result.truth).norm();
        const Eigen::MatrixXd S = 0.5 * (X[i] + X[i].transpose());
        inconsistent[i][k] =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues()(0) <= 0.0;
      }
      for (std::size_t v = 0; v < variants.size(); ++v) {
        hexapod::PhysicalOptions fit;
        fit.criterion = variants[v].criterion;
        fit.consistent = variants[v].consistent;
        fit.strut_masses = variants[v].strut_masses;
        // The experiment measures the estimator on its own simulated SI data: every trial's
        // estimate counts, however far a small noisy sample puts it.
        fit.plausibility_check = false;
        try {
          const hexapod::PhysicalEstimate e = hexapod::identify_physical(data.A, data.B, geometry, fit);
          if (!e.ok()) continue;
          errors[generic + v][k] = (e.M_p - result.truth).norm();
          inconsistent[generic + v][k] = !e.physically_consistent;
        } catch (const std::invalid_argument&) {
          // data that cannot identify the parameters (a rank-deficient A): a failure of this trial
        }
      }
    });
    PhysicalExperimentRow row;
    row.samples = m;
    for (std::size_t i = 0; i < count; ++i) {
      PhysicalMethodErrors me;
      me.name = i < generic ? std::string(to_string(options.methods[i])) : variants[i - generic].name;
      me.summary = summarize(errors[i]);
      for (std::size_t k = 0; k < monte_carlo.trials; ++k) {
        if (!std::isnan(errors[i][k]) && inconsistent[i][k]) ++me.inconsistent;
      }
      me.errors = std::move(errors[i]);
      row.methods.push_back(std::move(me));
    }
    result.rows.push_back(std::move(row));
  }
  return result;
}

namespace {

// Whether the row's k-th estimator is a generic method (they come first).
bool generic(const PhysicalExperimentResult& result, std::size_t k) {
  return k < result.options.methods.size();
}

}  // namespace

void set_estimators(PhysicalExperimentOptions& options, const std::vector<std::string>& names) {
  options.methods.clear();
  options.variants.clear();
  for (const std::string& name : names) {
    const std::optional<Method> method = parse_method(name);  // the selectable methods only
    if (method) {
      options.methods.push_back(*method);
    } else if (physical_variant(name)) {
      options.variants.push_back(name);
    } else {
      std::string known;
      for (Method m : kSelectableMethods) known += (known.empty() ? "" : ", ") + std::string(to_string(m));
      for (const std::string& v : physical_variant_names()) known += ", " + v;
      throw std::invalid_argument("unknown method '" + name + "' (the methods are " + known +
                                  "; a physical variant with :common or :each estimates the strut masses)");
    }
  }
}

std::optional<PhysicalComparison> compare_to_generic(const PhysicalExperimentResult& result,
                                                     const PhysicalExperimentRow& row) {
  const PhysicalMethodErrors* physical = nullptr;
  const PhysicalMethodErrors* best = nullptr;
  for (std::size_t k = 0; k < row.methods.size(); ++k) {
    const PhysicalMethodErrors& m = row.methods[k];
    if (m.summary.count == 0) continue;
    if (generic(result, k)) {
      if (best == nullptr || m.summary.mean < best->summary.mean) best = &m;
    } else if (m.name == "physical") {
      physical = &m;
    }
  }
  if (physical == nullptr || best == nullptr || !(best->summary.mean > 0.0)) return std::nullopt;
  return PhysicalComparison{best->name, physical->summary.mean / best->summary.mean};
}

}  // namespace spdfit::experiment
