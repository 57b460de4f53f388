// The physical-identification experiment as JSON and as a table for people.
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "spdfit/experiment/physical.hpp"
#include "spdfit/format.hpp"

namespace spdfit::experiment {

namespace {

using json = nlohmann::ordered_json;

json number(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

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

std::string to_json(const PhysicalExperimentResult& result) {
  const hexapod::SimulationOptions& s = result.options.simulation;
  json out;
  out["experiment"] = "physical";
  out["noise_var"] = s.noise_var;
  out["force_noise_var"] = s.force_noise_var.value_or(s.noise_var);
  out["signal_var"] = s.signal_var;
  out["distribution"] = std::string(hexapod::to_string(s.distribution));
  out["trials"] = result.trials;
  out["seed"] = result.seed;
  if (const std::optional<RigidBodyInertia>& p = result.options.payload) {
    json inertia = json::array();
    for (int i = 0; i < 3; ++i)
      inertia.push_back({number(p->inertia(i, 0)), number(p->inertia(i, 1)), number(p->inertia(i, 2))});
    out["payload"] = {
        {"mass", number(p->mass)},
        {"center_of_mass",
         {number(p->center_of_mass(0)), number(p->center_of_mass(1)), number(p->center_of_mass(2))}},
        {"inertia", inertia}};
  }
  json truth = json::array();
  for (Eigen::Index i = 0; i < result.truth.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < result.truth.cols(); ++j) row.push_back(number(result.truth(i, j)));
    truth.push_back(row);
  }
  out["truth"] = truth;
  json names = json::array();
  for (Method m : result.options.methods) names.push_back(std::string(to_string(m)));
  for (const std::string& v : result.options.variants) names.push_back(v);
  out["methods"] = names;
  json rows = json::array();
  for (const PhysicalExperimentRow& row : result.rows) {
    json r;
    r["samples"] = row.samples;
    json methods = json::object();
    for (const PhysicalMethodErrors& m : row.methods) {
      const Summary& x = m.summary;
      methods[m.name] = {
          {"mean", number(x.mean)}, {"std", number(x.std)},   {"median", number(x.median)},
          {"max", number(x.max)},   {"min", number(x.min)},   {"standard_error", number(x.standard_error())},
          {"count", x.count},       {"failures", x.failures}, {"inconsistent", m.inconsistent}};
    }
    r["methods"] = methods;
    const std::optional<PhysicalComparison> c = compare_to_generic(result, row);
    r["best_generic"] = c ? json(c->best_generic) : json(nullptr);
    r["physical_ratio"] = c ? number(c->ratio) : json(nullptr);
    rows.push_back(r);
  }
  out["rows"] = rows;
  return out.dump(2) + "\n";
}

std::string report(const PhysicalExperimentResult& result) {
  const hexapod::SimulationOptions& s = result.options.simulation;
  std::ostringstream out;
  out << "Physical identification experiment: "
      << (result.options.geometry ? "the given hexapod" : "the built-in hexapod")
      << ", M_p of its nominal payload";
  if (const std::optional<RigidBodyInertia>& p = result.options.payload) {
    const PrincipalInertia principal = principal_inertia(p->inertia);
    out << " replaced by a payload of " << format_number(p->mass, Precision::Full) << " kg, centre of mass ("
        << format_number(p->center_of_mass(0)) << ", " << format_number(p->center_of_mass(1)) << ", "
        << format_number(p->center_of_mass(2)) << ") m, principal moments "
        << format_number(principal.moments(0)) << ", " << format_number(principal.moments(1)) << ", "
        << format_number(principal.moments(2)) << " kg m^2";
  }
  out << ";\n"
      << hexapod::to_string(s.distribution) << " noise of variance "
      << format_number(s.noise_var, Precision::Medium) << " in every entry of A";
  if (s.force_noise_var && *s.force_noise_var != s.noise_var) {
    out << " and " << format_number(*s.force_noise_var, Precision::Medium) << " in every entry of B";
  } else {
    out << " and B";
  }
  out << "; " << result.trials << " trials, seed " << result.seed << ".\n"
      << "Mean error ||M_hat - M_p||_F +- its standard error:\n\n";
  const std::vector<PhysicalMethodErrors> none;
  const std::vector<PhysicalMethodErrors>& first = result.rows.empty() ? none : result.rows.front().methods;
  char cell[64];
  out << "     m";
  for (const PhysicalMethodErrors& m : first) {
    std::snprintf(cell, sizeof cell, "  %17s", m.name.c_str());
    out << cell;
  }
  out << "   physical / best generic\n";
  bool any_inconsistent = false;
  for (const PhysicalExperimentRow& row : result.rows) {
    std::snprintf(cell, sizeof cell, "%6ld", static_cast<long>(row.samples));
    out << cell;
    for (const PhysicalMethodErrors& m : row.methods) {
      const std::string text =
          format_fixed(m.summary.mean, 3) + " +- " + format_fixed(m.summary.standard_error(), 3);
      std::snprintf(cell, sizeof cell, "  %17s", text.c_str());
      out << cell;
      any_inconsistent = any_inconsistent || m.inconsistent > 0;
    }
    if (const std::optional<PhysicalComparison> c = compare_to_generic(result, row)) {
      out << "   " << format_fixed(c->ratio, 2) << " (" << c->best_generic << ")";
    }
    out << "\n";
  }
  out << "\nEstimates not physically consistent (generic: not positive definite), of " << result.trials
      << ":";
  if (!any_inconsistent) {
    out << " none\n";
    return out.str();
  }
  out << "\n     m";
  for (const PhysicalMethodErrors& m : first) {
    std::snprintf(cell, sizeof cell, "  %17s", m.name.c_str());
    out << cell;
  }
  out << "\n";
  for (const PhysicalExperimentRow& row : result.rows) {
    std::snprintf(cell, sizeof cell, "%6ld", static_cast<long>(row.samples));
    out << cell;
    for (const PhysicalMethodErrors& m : row.methods) {
      std::snprintf(cell, sizeof cell, "  %17zu", m.inconsistent);
      out << cell;
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace spdfit::experiment
