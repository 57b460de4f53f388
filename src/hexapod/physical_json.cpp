// physical_json: the physical estimate in the JSON contract of `hexapod identify --json`.
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "render/fit_result_json.hpp"
#include "render/json_values.hpp"
#include "spdfit/hexapod/physical.hpp"

namespace spdfit::hexapod {

namespace {

using json = nlohmann::ordered_json;

json number(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json vector(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number(v(i)));
  return out;
}

json matrix(const Eigen::MatrixXd& M) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) rows.push_back(vector(M.row(i).transpose()));
  return rows;
}

// A strut-mass value: one number for a common mass, else the list.
json struts(const Eigen::MatrixXd& values, StrutMasses kind) {
  return kind == StrutMasses::Common && values.size() == 1 ? number(values(0, 0)) : vector(values.reshaped());
}

json spectrum(const SpectrumUncertainty& s) {
  json clusters = json::array();
  for (const std::vector<Eigen::Index>& c : s.clusters) clusters.push_back(c);
  return {{"estimate", vector(s.estimate)}, {"standard_errors", vector(s.standard_errors)},
          {"lower", vector(s.lower)},       {"upper", vector(s.upper)},
          {"clusters", clusters},           {"failed", s.failed}};
}

// The keys with bootstrap uncertainty, each from one member of EntryUncertainty.
json entries(const PhysicalBootstrap& b, Eigen::MatrixXd EntryUncertainty::*member, StrutMasses kind) {
  return {{"mass", number((b.mass.*member)(0, 0))},
          {"center_of_mass", vector(b.center_of_mass.*member)},
          {"inertia", matrix(b.inertia.*member)},
          {"principal_moments", vector(b.principal_moments.*member)},
          {"strut_mass", struts(b.strut_mass.*member, kind)},
          {"M_p", matrix(b.M_p.*member)}};
}

}  // namespace

std::string physical_json(const PhysicalEstimate& e) {
  json out;
  out["status"] = to_string(e.status);
  if (!e.ok()) {
    out["error"] = e.message;
    spdfit::detail::put_warnings(out, e.warnings);
    return out.dump(2) + "\n";
  }
  out["mass"] = number(e.payload.mass);
  out["center_of_mass"] = vector(e.payload.center_of_mass);
  out["inertia"] = matrix(e.payload.inertia);
  out["principal_moments"] = vector(e.principal.moments);
  out["principal_axes"] = matrix(e.principal.axes);
  out["strut_mass"] = struts(e.strut_mass, e.strut_masses);
  out["strut_masses"] = std::string(to_string(e.strut_masses));
  out["M_p"] = matrix(e.M_p);
  out["M_p_eigenvalues"] = vector(e.M_p_eigenvalues);
  if (e.modes_hz) out["modes_hz"] = vector(*e.modes_hz);
  out["pseudo_inertia_min_eig"] = number(e.pseudo_inertia_min_eig);
  out["physically_consistent"] = e.physically_consistent;
  out["certificate"] = {{"stationarity", number(e.certificate.stationarity)},
                        {"primal_min_eig", number(e.certificate.primal_min_eig)},
                        {"dual_min_eig", number(e.certificate.dual_min_eig)},
                        {"complementarity", number(e.certificate.complementarity)}};
  out["start_certificate"] = {{"primal_min_eig", number(e.start_certificate.primal_min_eig)},
                              {"dual_min_eig", number(e.start_certificate.dual_min_eig)},
                              {"complementarity", number(e.start_certificate.complementarity)},
                              {"duality_gap", number(e.start_certificate.duality_gap)}};
  out["criterion"] = number(e.criterion);
  out["criterion_kind"] = std::string(to_string(e.criterion_kind));
  out["consistent"] = e.consistent_requested;
  out["iterations"] = e.iterations;
  out["converged"] = e.converged;
  out["design"] = {{"parameters", e.design.parameters},
                   {"rank", e.design.rank},
                   {"condition", number(e.design.condition)},
                   {"length_scale", number(e.design.length_scale)},
                   {"confounded", e.design.confounded}};
  out["m"] = e.m;
  out["rank_a"] = e.rank_a;
  out["offsets"] = e.tare_b.size()      ? json{{"mode", "rest"}, {"a", vector(e.tare_a)}, {"b", vector(e.tare_b)}}
                   : e.offsets_c.size() ? json{{"mode", "estimate"}, {"c", vector(e.offsets_c)}}
                                        : json{{"mode", "none"}};
  // The robust report as the fit's (render/fit_result_json.cpp), in this document's key order.
  if (e.robust) out["robust"] = json::parse(spdfit::detail::robust_json(*e.robust, spdfit::JsonStyle::Contract).dump());
  spdfit::detail::put_warnings(out, e.warnings);
  if (const auto& b = e.bootstrap) {
    out["standard_errors"] = entries(*b, &EntryUncertainty::standard_errors, e.strut_masses);
    out["interval"] = {{"level", b->level},
                       {"lower", entries(*b, &EntryUncertainty::lower, e.strut_masses)},
                       {"upper", entries(*b, &EntryUncertainty::upper, e.strut_masses)}};
    json boot = {{"replicates", b->replicates}, {"failed", b->failed}, {"seed", b->seed},
                 {"M_p_eigenvalues", spectrum(b->M_p_eigenvalues)}};
    if (b->modes_hz) boot["modes_hz"] = spectrum(*b->modes_hz);
    out["bootstrap"] = std::move(boot);
  }
  return out.dump(2) + "\n";
}

}  // namespace spdfit::hexapod
