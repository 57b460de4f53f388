// The physical-identification experiment as JSON and as a table for people.
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "render/json_values.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/format.hpp"

namespace spdfit::experiment {

namespace {

using json = spdfit::detail::OrderedJson;
using spdfit::detail::number_json;

}  // namespace

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
      inertia.push_back({number_json(p->inertia(i, 0)), number_json(p->inertia(i, 1)), number_json(p->inertia(i, 2))});
    out["payload"] = {
        {"mass", number_json(p->mass)},
        {"center_of_mass",
         {number_json(p->center_of_mass(0)), number_json(p->center_of_mass(1)), number_json(p->center_of_mass(2))}},
        {"inertia", inertia}};
  }
  json truth = json::array();
  for (Eigen::Index i = 0; i < result.truth.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < result.truth.cols(); ++j) row.push_back(json(number_json(result.truth(i, j))));
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
          {"mean", number_json(x.mean)}, {"std", number_json(x.std)},   {"median", number_json(x.median)},
          {"max", number_json(x.max)},   {"min", number_json(x.min)},   {"standard_error", number_json(x.standard_error())},
          {"count", x.count},       {"failures", x.failures}, {"inconsistent", m.inconsistent}};
    }
    r["methods"] = methods;
    const std::optional<PhysicalComparison> c = compare_to_generic(result, row);
    r["best_generic"] = c ? json(c->best_generic) : json(nullptr);
    r["physical_ratio"] = c ? json(number_json(c->ratio)) : json(nullptr);
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
