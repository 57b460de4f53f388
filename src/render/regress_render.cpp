// `spdfit physical regress`'s result: JSON (physical/regress.hpp's to_json) and the report.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "render/json_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit::physical {

namespace {

using spdfit::detail::matrix_json;
using spdfit::detail::number_json;
using spdfit::detail::OrderedJson;
using spdfit::detail::vector_json;

OrderedJson certificate_json(const Certificate& c) {
  return {{"stationarity", number_json(c.stationarity)},
          {"primal_min_eig", number_json(c.primal_min_eig)},
          {"dual_min_eig", number_json(c.dual_min_eig)},
          {"complementarity", number_json(c.complementarity)},
          {"duality_gap", number_json(c.duality_gap)}};
}

std::string fixed(double value) {
  if (!std::isfinite(value)) return "undetermined";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

std::string to_json(const RegressResult& r) {
  OrderedJson out;
  out["status"] = to_string(r.status);
  if (!r.ok()) {
    out["error"] = r.message;
    spdfit::detail::put_warnings(out, r.warnings);
    return out.dump(2) + "\n";
  }
  out["bodies"] = r.bodies;
  out["param_order"] = std::string(to_string(r.param_order));
  out["consistent"] = r.consistent_requested;
  out["prior"] = r.prior_used;
  out["samples"] = r.samples;
  out["outputs"] = r.outputs;
  out["rows"] = r.rows;
  out["names"] = r.names;
  out["parameters"] = vector_json(r.parameters);
  OrderedJson bodies = OrderedJson::array();
  for (const RegressBody& b : r.body) {
    bodies.push_back({{"mass", number_json(b.inertia.mass)},
                      {"center_of_mass", vector_json(b.inertia.center_of_mass)},
                      {"inertia", matrix_json(b.inertia.inertia)},
                      {"parameters", vector_json(b.parameters)},
                      {"pseudo_inertia_min_eig", number_json(b.pseudo_inertia_min_eig)},
                      {"physically_consistent", b.physically_consistent},
                      {"determined", b.determined}});
  }
  out["body"] = bodies;
  out["extra"] = vector_json(r.extra);
  out["rank"] = r.identifiability.rank;
  out["condition"] = number_json(r.identifiability.condition);
  OrderedJson base = OrderedJson::array();
  for (Eigen::Index i = 0; i < r.identifiability.rank; ++i) {
    base.push_back({{"combination", r.identifiability.base_names[static_cast<std::size_t>(i)]},
                    {"coefficients", vector_json(r.identifiability.base.row(i).transpose())},
                    {"value", number_json(r.base_parameters(i))}});
  }
  out["base_parameters"] = base;
  OrderedJson undetermined = OrderedJson::array();
  for (const UndeterminedCombination& u : r.identifiability.undetermined) {
    undetermined.push_back(
        {{"parameters", u.parameters}, {"coefficients", vector_json(u.coefficients)}, {"combination", u.text}});
  }
  out["undetermined"] = undetermined;
  out["criterion"] = number_json(r.criterion);
  out["criterion_unconstrained"] = number_json(r.criterion_unconstrained);
  out["residual_rms"] = number_json(r.residual_rms);
  out["certificate"] = certificate_json(r.certificate);
  out["iterations"] = r.iterations;
  out["converged"] = r.converged;
  out["physically_consistent"] = r.physically_consistent;
  spdfit::detail::put_warnings(out, r.warnings);
  if (r.bootstrap) {
    const RegressBootstrap& b = *r.bootstrap;
    out["bootstrap"] = {{"replicates", b.replicates},
                        {"failed", b.failed},
                        {"seed", b.seed},
                        {"level", b.level},
                        {"parameters",
                         {{"standard_errors", vector_json(b.parameter_se)},
                          {"lower", vector_json(b.parameter_lower)},
                          {"upper", vector_json(b.parameter_upper)}}},
                        {"base_parameters",
                         {{"standard_errors", vector_json(b.base_se)},
                          {"lower", vector_json(b.base_lower)},
                          {"upper", vector_json(b.base_upper)}}}};
  }
  return out.dump(2) + "\n";
}

std::string report(const RegressResult& r) {
  std::ostringstream out;
  if (!r.ok()) {
    out << "physically consistent regression failed: " << r.message << "\n";
    return out.str();
  }
  out << "physical regress: " << r.bodies << (r.bodies == 1 ? " body" : " bodies") << ", " << r.samples
      << " samples x " << r.outputs << (r.outputs == 1 ? " output" : " outputs") << " (" << r.rows << " rows), "
      << r.parameters.size() << " parameters (" << to_string(r.param_order) << " order)"
      << (r.consistent_requested ? ", physically consistent" : ", unconstrained")
      << (r.prior_used ? ", with a prior" : "") << "\n";
  for (std::size_t k = 0; k < r.body.size(); ++k) {
    const RegressBody& b = r.body[k];
    out << "  body " << k + 1 << ": mass " << fixed(b.inertia.mass) << " kg, centre of mass (" << fixed(b.inertia.center_of_mass(0))
        << ", " << fixed(b.inertia.center_of_mass(1)) << ", " << fixed(b.inertia.center_of_mass(2)) << ") m"
        << (b.physically_consistent ? "" : "  NOT physically consistent") << "\n";
    if (b.inertia.inertia.allFinite()) {
      out << "          inertia about the centre of mass [" << fixed(b.inertia.inertia(0, 0)) << " "
          << fixed(b.inertia.inertia(0, 1)) << " " << fixed(b.inertia.inertia(0, 2)) << "; "
          << fixed(b.inertia.inertia(1, 1)) << " " << fixed(b.inertia.inertia(1, 2)) << "; "
          << fixed(b.inertia.inertia(2, 2)) << "] kg m^2\n";
    }
  }
  if (r.extra.size() > 0) {
    out << "  extra parameters:";
    for (Eigen::Index j = 0; j < r.extra.size(); ++j) out << " " << fixed(r.extra(j));
    out << "\n";
  }
  out << "  rank " << r.identifiability.rank << " of " << r.identifiability.parameters << ", condition "
      << format_number(r.identifiability.condition) << "; base parameters:\n";
  for (Eigen::Index i = 0; i < r.identifiability.rank; ++i) {
    out << "    " << r.identifiability.base_names[static_cast<std::size_t>(i)] << " = " << fixed(r.base_parameters(i));
    if (r.bootstrap) out << " +- " << fixed(r.bootstrap->base_se(i));
    out << "\n";
  }
  for (const UndeterminedCombination& u : r.identifiability.undetermined) out << "  undetermined: " << u.text << "\n";
  out << "  criterion " << format_number(r.criterion) << " (unconstrained " << format_number(r.criterion_unconstrained)
      << "), residual RMS " << format_number(r.residual_rms) << "\n";
  if (r.consistent_requested) {
    out << "  certificate: stationarity " << format_number(r.certificate.stationarity) << ", dual min eig "
        << format_number(r.certificate.dual_min_eig) << ", duality gap " << format_number(r.certificate.duality_gap)
        << ", " << r.iterations << " Newton steps" << (r.converged ? "" : " (not converged)") << "\n";
  }
  return out.str();
}

}  // namespace spdfit::physical
