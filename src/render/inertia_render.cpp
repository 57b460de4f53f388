// `spdfit inertia repair`: a body's repair as JSON (it reads back as an inertia file,
// inertia/inertia_file.cpp) and a URDF's repairs as a report for people.
#include <cstdio>
#include <string>

#include "render/json_values.hpp"
#include "spdfit/inertia_repair.hpp"

namespace spdfit {

std::string inertia_repair_json(const InertiaRepairResult& result) {
  spdfit::detail::OrderedJson out;
  out["mass"] = result.repaired.mass;
  out["center_of_mass"] = spdfit::detail::vector_json(result.repaired.center_of_mass);
  out["inertia"] = spdfit::detail::matrix_json(result.repaired.inertia);
  out["changed"] = result.changed;
  out["distance"] = result.distance;
  out["certificate"] = {{"primal_min_eig", result.certificate.primal_min_eig},
                        {"dual_min_eig", result.certificate.dual_min_eig},
                        {"complementarity", result.certificate.complementarity}};
  out["min_eig"] = result.floor;
  out["principal_moments"] = spdfit::detail::vector_json(result.principal_moments);
  out["principal_moments_before"] = spdfit::detail::vector_json(result.principal_moments_before);
  out["second_moments_before"] = spdfit::detail::vector_json(result.second_moments_before);
  out["metric"] = std::string(to_string(result.metric));
  spdfit::detail::put_warnings(out, result.warnings);
  return out.dump(2) + "\n";
}

std::string urdf_repair_report(const UrdfRepairResult& result) {
  auto g = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return std::string(buffer);
  };
  auto moments = [&g](const Eigen::Vector3d& I) { return g(I(0)) + ", " + g(I(1)) + ", " + g(I(2)); };
  std::string out;
  for (const UrdfLinkRepair& l : result.links) {
    const InertiaRepairResult& r = l.result;
    out += "link \"" + l.link + "\" (line " + std::to_string(l.line) + "): ";
    if (!r.changed) {
      out += "consistent (principal moments " + moments(r.principal_moments) + " kg m^2)\n";
      for (const Warning& w : r.warnings) out += "  warning: " + w.text + "\n";
      continue;
    }
    const Eigen::Vector3d& I = r.principal_moments_before;
    out += "repaired: principal moments " + moments(I) + " kg m^2 ";
    out += I(2) > I(0) + I(1) ? "break the triangle inequality (" + g(I(2)) + " > " + g(I(0)) + " + " + g(I(1)) + ")"
                              : "meet the triangle inequality with less than the margin " + g(2 * r.floor);
    out += "; now " + moments(r.principal_moments) + " kg m^2, moved by " + g(r.distance) + " kg m^2\n";
    for (const Warning& w : r.warnings) out += "  warning: " + w.text + "\n";
  }
  out += std::to_string(result.changed()) + " of " + std::to_string(result.links.size()) + " links repaired\n";
  return out;
}

}  // namespace spdfit
