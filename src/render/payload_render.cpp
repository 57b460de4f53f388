// `spdfit payload identify`'s and `payload design`'s results: JSON (payload/identify.hpp's and
// payload/design.hpp's to_json) and the reports.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "render/fit_result_json.hpp"
#include "render/json_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"

namespace spdfit::payload {

namespace {

using spdfit::detail::matrix_json;
using spdfit::detail::number_json;
using spdfit::detail::OrderedJson;
using spdfit::detail::vector_json;

// A matrix that is all NaN (not determined) as null, else its rows.
OrderedJson maybe_matrix(const Eigen::Matrix3d& M) {
  return M.array().isNaN().all() ? OrderedJson(nullptr) : OrderedJson(matrix_json(M));
}

OrderedJson group_json(double mass, const Eigen::Vector3d& c, const Eigen::Matrix3d& I, const Eigen::Vector3d& moments,
                       const Eigen::Vector3d& bf, const Eigen::Vector3d& bt) {
  return {{"mass", number_json(mass)},
          {"center_of_mass", vector_json(c)},
          {"inertia", maybe_matrix(I)},
          {"principal_moments", vector_json(moments)},
          {"force_bias", vector_json(bf)},
          {"torque_bias", vector_json(bt)}};
}

OrderedJson interval_json(const PayloadEstimate::Bootstrap& b, Eigen::MatrixXd Interval::*member) {
  return group_json((b.mass.*member)(0, 0), b.center_of_mass.*member, b.inertia.*member, b.principal_moments.*member,
                    b.force_bias.*member, b.torque_bias.*member);
}

std::string g(double value, int digits = 6) {
  if (!std::isfinite(value)) return "undetermined";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string with_se(double value, double se) {
  if (!std::isfinite(value)) return "undetermined";
  std::string out = g(value);
  if (std::isfinite(se)) out += " +- " + g(se, 2);
  return out;
}

// An interval "[12.4600, 12.4974]" to its standard error's third significant digit, so that
// whether a value lies inside can be read.
std::string bounds(const Interval& interval, Eigen::Index i) {
  const double lower = interval.lower(i, 0), upper = interval.upper(i, 0);
  if (!std::isfinite(lower) || !std::isfinite(upper)) return "undetermined";
  const int decimals = interval_decimals(interval.standard_errors(i, 0));
  return "[" + format_fixed(lower, decimals) + ", " + format_fixed(upper, decimals) + "]";
}

std::string vector_with_se(const Eigen::Vector3d& v, const Eigen::Vector3d& se) {
  return "(" + with_se(v(0), se(0)) + ", " + with_se(v(1), se(1)) + ", " + with_se(v(2), se(2)) + ")";
}

}  // namespace

std::string to_json(const PayloadEstimate& e) {
  OrderedJson out;
  out["status"] = to_string(e.status);
  if (!e.ok()) {
    out["error"] = e.message;
    spdfit::detail::put_warnings(out, e.warnings);
    return out.dump(2) + "\n";
  }
  out["model"] = e.moving ? "moving" : "static";
  out["criterion"] = std::string(to_string(e.criterion));
  out["consistent"] = e.consistent_requested;
  out["wrench_sign"] = std::string(to_string(e.wrench_sign));
  out["frame"] = std::string(to_string(e.frame));
  out["samples"] = e.samples;
  out["mass"] = number_json(e.mass);
  out["center_of_mass"] = vector_json(e.center_of_mass);
  out["inertia"] = maybe_matrix(e.inertia);
  out["inertia_origin"] = maybe_matrix(e.inertia_origin);
  out["principal_moments"] = vector_json(e.principal.moments);
  out["principal_axes"] = maybe_matrix(e.principal.axes);
  out["force_bias"] = vector_json(e.force_bias);
  out["torque_bias"] = vector_json(e.torque_bias);
  out["standard_errors"] = group_json(e.mass_se, e.center_of_mass_se, e.inertia_se, e.principal_moments_se,
                                      e.force_bias_se, e.torque_bias_se);
  out["names"] = e.names;
  out["parameters"] = vector_json(e.parameters);
  out["parameter_standard_errors"] = vector_json(e.standard_errors);
  out["residual_rms"] = vector_json(e.residual_rms);
  out["condition"] = number_json(e.identifiability.condition);
  out["rank"] = e.identifiability.rank;
  OrderedJson undetermined = OrderedJson::array();
  for (const physical::UndeterminedCombination& u : e.identifiability.undetermined) {
    undetermined.push_back(
        {{"parameters", u.parameters}, {"coefficients", vector_json(u.coefficients)}, {"combination", u.text}});
  }
  out["undetermined"] = undetermined;
  out["unconstrained_mass"] = number_json(e.unconstrained_mass);
  out["unconstrained_mass_se"] = number_json(e.unconstrained_mass_se);
  out["criterion_value"] = number_json(e.criterion_value);
  out["pseudo_inertia_min_eig"] = number_json(e.pseudo_inertia_min_eig);
  out["physically_consistent"] = e.physically_consistent;
  out["constraint_active"] = e.constraint_active;
  out["certificate"] = {{"stationarity", number_json(e.certificate.stationarity)},
                        {"primal_min_eig", number_json(e.certificate.primal_min_eig)},
                        {"dual_min_eig", number_json(e.certificate.dual_min_eig)},
                        {"complementarity", number_json(e.certificate.complementarity)},
                        {"duality_gap", number_json(e.certificate.duality_gap)}};
  out["iterations"] = e.iterations;
  out["converged"] = e.converged;
  out["distinct_orientations"] = e.distinct_orientations;
  spdfit::detail::put_warnings(out, e.warnings);
  // The robust report as fit's (render/fit_result_json.cpp).
  if (e.robust) out["robust"] = OrderedJson(spdfit::detail::robust_json(*e.robust, spdfit::JsonStyle::Contract));
  if (e.bootstrap) {
    const PayloadEstimate::Bootstrap& b = *e.bootstrap;
    out["bootstrap"] = {{"replicates", b.replicates}, {"failed", b.failed}, {"seed", b.seed}, {"level", b.level}};
    out["bootstrap_standard_errors"] = interval_json(b, &Interval::standard_errors);
    out["interval"] = {
        {"level", b.level}, {"lower", interval_json(b, &Interval::lower)}, {"upper", interval_json(b, &Interval::upper)}};
  }
  return out.dump(2) + "\n";
}

std::string report(const PayloadEstimate& e) {
  std::ostringstream out;
  if (!e.ok()) {
    out << "payload identification failed: " << e.message << "\n";
    return out.str();
  }
  out << "payload: " << e.samples << " samples, " << (e.moving ? "moving" : "static") << " poses ("
      << e.distinct_orientations << (e.distinct_orientations >= 1000 ? "+" : "") << " distinct gravity directions), "
      << (e.criterion == Criterion::LeastSquares ? "least squares" : "errors in variables")
      << (e.consistent_requested ? ", physically consistent" : ", unconstrained") << "\n";
  out << "  mass            " << with_se(e.mass, e.mass_se) << " kg\n";
  out << "  centre of mass  " << vector_with_se(e.center_of_mass, e.center_of_mass_se) << " m (sensor frame)\n";
  if (e.moving) {
    out << "  inertia about the centre of mass (kg m^2, sensor axes):\n";
    for (int i = 0; i < 3; ++i) {
      out << "    ";
      for (int j = 0; j < 3; ++j) out << (j ? "  " : "") << with_se(e.inertia(i, j), e.inertia_se(i, j));
      out << "\n";
    }
    out << "  principal moments " << vector_with_se(e.principal.moments, e.principal_moments_se) << " kg m^2\n";
    if (e.principal.axes.allFinite()) {
      out << "  principal axes  ";
      for (int j = 0; j < 3; ++j) {
        out << (j ? ", (" : "(") << g(e.principal.axes(0, j), 4) << ", " << g(e.principal.axes(1, j), 4) << ", "
            << g(e.principal.axes(2, j), 4) << ")";
      }
      out << " (one per moment, sensor axes)\n";
    }
  } else {
    out << "  inertia         not determined by static poses\n";
  }
  out << "  force bias      " << vector_with_se(e.force_bias, e.force_bias_se) << " N\n";
  out << "  torque bias     " << vector_with_se(e.torque_bias, e.torque_bias_se) << " N m\n";
  if (e.robust) out << "  " << spdfit::detail::robust_line(*e.robust);
  if (e.bootstrap) {
    const PayloadEstimate::Bootstrap& b = *e.bootstrap;
    out << "  bootstrap (" << b.replicates << " replicates, " << g(100.0 * b.level, 3) << "% intervals): mass "
        << bounds(b.mass, 0) << " kg, centre of mass x " << bounds(b.center_of_mass, 0) << ", y "
        << bounds(b.center_of_mass, 1) << ", z " << bounds(b.center_of_mass, 2) << " m\n";
  }
  out << "  residual RMS    force (" << g(e.residual_rms(0), 3) << ", " << g(e.residual_rms(1), 3) << ", "
      << g(e.residual_rms(2), 3) << ") N, torque (" << g(e.residual_rms(3), 3) << ", " << g(e.residual_rms(4), 3)
      << ", " << g(e.residual_rms(5), 3) << ") N m\n";
  out << "  regressor       rank " << e.identifiability.rank << " of " << e.identifiability.parameters
      << ", condition " << format_number(e.identifiability.condition) << " (unit-norm columns)\n";
  for (const physical::UndeterminedCombination& u : e.identifiability.undetermined) {
    out << "  undetermined    " << u.text << "\n";
  }
  if (e.consistent_requested) {
    out << "  consistency     " << (e.constraint_active ? "constraint active" : "constraint inactive")
        << " (unconstrained mass " << with_se(e.unconstrained_mass, e.unconstrained_mass_se) << " kg); certificate: "
        << "stationarity " << format_number(e.certificate.stationarity) << ", dual min eig "
        << format_number(e.certificate.dual_min_eig);
    if (std::isfinite(e.certificate.duality_gap)) out << ", duality gap " << format_number(e.certificate.duality_gap);
    out << "\n";
  }
  return out.str();
}

std::string to_json(const DesignResult& r) {
  OrderedJson out;
  out["criterion"] = std::string(to_string(r.criterion));
  out["poses"] = r.poses;
  out["candidates"] = r.candidates;
  std::vector<Eigen::Index> one_based;
  for (Eigen::Index i : r.chosen) one_based.push_back(i + 1);
  out["chosen"] = one_based;
  out["log_det"] = number_json(r.score.log_det);
  out["condition"] = number_json(r.score.condition);
  out["se_mass"] = number_json(r.score.se_mass);
  out["se_center_of_mass"] = vector_json(r.score.se_center_of_mass);
  out["se_center_of_mass_norm"] = number_json(r.score.se_center_of_mass_norm);
  out["random"] = {{"choices", r.random},
                   {"log_det", vector_json(r.random_log_det)},
                   {"se_mass", vector_json(r.random_se_mass)},
                   {"se_center_of_mass_norm", vector_json(r.random_se_center_of_mass)},
                   {"condition", vector_json(r.random_condition)},
                   {"beats", r.beats_random}};
  out["distinct_candidates"] = r.distinct_candidates;
  spdfit::detail::put_warnings(out, r.warnings);
  return out.dump(2) + "\n";
}

std::string report(const DesignResult& r) {
  std::ostringstream out;
  out << "payload design: " << r.poses << " of " << r.candidates << " candidate poses (" << r.distinct_candidates
      << " distinct gravity directions), " << to_string(r.criterion) << "-optimal\n";
  out << "  chosen rows (1-based):";
  for (Eigen::Index i : r.chosen) out << " " << i + 1;
  out << "\n";
  out << "  log det F " << format_number(r.score.log_det) << ", condition " << format_number(r.score.condition)
      << ", predicted standard error of m " << format_number(r.score.se_mass) << " kg, of c "
      << format_number(r.score.se_center_of_mass_norm) << " m\n";
  if (r.random > 0) {
    out << "  " << r.random << " random choices of " << r.poses
        << " poses (10th / 50th / 90th percentiles): standard error of m " << format_number(r.random_se_mass(0)) << " / "
        << format_number(r.random_se_mass(1)) << " / " << format_number(r.random_se_mass(2)) << " kg, of c "
        << format_number(r.random_se_center_of_mass(0)) << " / " << format_number(r.random_se_center_of_mass(1)) << " / "
        << format_number(r.random_se_center_of_mass(2)) << " m, log det " << format_number(r.random_log_det(0)) << " / "
        << format_number(r.random_log_det(1)) << " / " << format_number(r.random_log_det(2)) << "\n";
    out << "  the chosen design's standard error of m is at most that of " << format_number(100.0 * r.beats_random)
        << "% of the random choices\n";
  }
  return out.str();
}

}  // namespace spdfit::payload
