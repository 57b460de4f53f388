// `linkage synthesize`'s result as JSON and as a report for people.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "render/json_values.hpp"
#include "render/linkage_render.hpp"
#include "spdfit/linkage/synthesize_request.hpp"

namespace spdfit::linkage {

namespace {

using detail::four_decimals;
using detail::full_g;
using detail::in_degrees;
using detail::kRadiansPerDegree;
using detail::span_json;

nlohmann::json degrees_json(const Eigen::VectorXd& v) { return spdfit::detail::vector_json(Eigen::VectorXd(v / kRadiansPerDegree)); }

nlohmann::json solution_json(const LinkageSolution& s, bool with_iterations) {
  nlohmann::json out;
  out["k"] = spdfit::detail::vector_json(s.k);
  if (s.lengths) {
    out["lengths"] = {{"a1", s.lengths->a1}, {"a2", s.lengths->a2}, {"a3", s.lengths->a3}, {"a4", s.lengths->a4}};
  } else {
    out["lengths"] = nullptr;
  }
  out["design_error_norm"] = spdfit::detail::number_json(s.design_error_norm);
  out["structural_error_rms_deg"] = spdfit::detail::number_json(in_degrees(s.structural_error_rms));
  out["structural_error_max_deg"] = spdfit::detail::number_json(in_degrees(s.structural_error_max));
  if (with_iterations) {
    out["iterations"] = s.iterations;
    out["final_step_norm"] = s.final_step_norm;
  }
  out["dial_zeros_deg"] = {{"alpha", in_degrees(s.dial_zeros.alpha)}, {"beta", in_degrees(s.dial_zeros.beta)}};
  out["phi_generated_deg"] = degrees_json(s.phi_generated);
  if (s.check) {
    out["grashof"] = to_string(s.check->grashof);
    out["transmission_angle_deg"] = span_json(s.check->transmission);
    out["branch_defect"] = s.check->branch_defect;
    out["branch_defect_reason"] = s.check->branch_defect_reason;
    out["dead_points_deg"] = spdfit::detail::vector_json(Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(
                                             s.check->dead_points.data(), Eigen::Index(s.check->dead_points.size())) /
                                         kRadiansPerDegree));
  }
  return out;
}

nlohmann::json synthesis_json(const SynthesisResult& r, const SynthesisRun& p) {
  nlohmann::json out;
  out["design"] = solution_json(r.design, false);
  out["structural"] = solution_json(r.structural, true);
  out["condition_number"] = spdfit::detail::number_json(r.condition_number);
  out["scaled_condition_number"] = spdfit::detail::number_json(r.scaled_condition_number);
  out["rank_decided_on"] = "column-scaled";
  const MotionCheck& check = *r.structural.check;
  out["grashof"] = to_string(check.grashof);
  out["transmission_angle_deg"] = span_json(check.transmission);
  out["branch_defect"] = check.branch_defect;
  out["m"] = r.positions;
  out["source"] = p.source;
  out["precision_point"] = r.precision_point;
  out["dial_zeros_fitted"] = r.dial_zeros_fitted;
  out["rank"] = r.rank;
  out["used_svd"] = r.used_svd;
  out["branch"] = r.branch;
  out["pairs"] = {{"psi_deg", degrees_json(r.psi)}, {"phi_deg", degrees_json(r.phi)}};
  out["weights"] = p.weights.size() ? spdfit::detail::vector_json(p.weights) : nlohmann::json(nullptr);
  out["warnings"] = texts(r.warnings);
  return out;
}

std::string synthesis_text(const SynthesisResult& r, const SynthesisRun& p, bool positions) {
  std::ostringstream out;
  const LinkageSolution& d = r.design;
  const LinkageSolution& s = r.structural;
  out << "Four-bar function generator, " << r.positions << " prescribed positions: " << p.source
      << (p.weights.size() ? ", weighted" : "") << "\n";
  out << "synthesis matrix S: condition number " << full_g(r.condition_number) << ", rank " << r.rank
      << (r.used_svd ? " (edited SVD, minimum norm)" : "") << " (column-scaled: condition number "
      << full_g(r.scaled_condition_number) << ")" << (r.precision_point ? "; precision points: exact" : "")
      << "\nassembly branch followed: " << (r.branch > 0 ? "+1" : "-1") << "\n\n";
  char line[200];
  const std::string structural_title =
      r.precision_point ? "structural (= design)"
                        : "structural (Gauss-Newton, " + std::to_string(s.iterations) + " it.)";
  std::snprintf(line, sizeof line, "%-26s %-20s %s\n", "", "design error", structural_title.c_str());
  out << line;
  auto row = [&](const char* name, const std::string& a, const std::string& b) {
    std::snprintf(line, sizeof line, "%-26s %-20s %s\n", name, a.c_str(), b.c_str());
    out << line;
  };
  for (int i = 0; i < 3; ++i) row(i == 0 ? "k1" : (i == 1 ? "k2" : "k3"), full_g(d.k(i)), full_g(s.k(i)));
  auto length = [](const LinkageSolution& x, int i) {
    if (!x.lengths) return std::string("-");
    const double a[4] = {x.lengths->a1, x.lengths->a2, x.lengths->a3, x.lengths->a4};
    return full_g(a[i]);
  };
  const char* names[4] = {"a1 (ground)", "a2 (input)", "a3 (coupler)", "a4 (output)"};
  for (int i = 0; i < 4; ++i) row(names[i], length(d, i), length(s, i));
  row("alpha, beta (deg)", four_decimals(in_degrees(d.dial_zeros.alpha)) + ", " + four_decimals(in_degrees(d.dial_zeros.beta)),
      four_decimals(in_degrees(s.dial_zeros.alpha)) + ", " + four_decimals(in_degrees(s.dial_zeros.beta)));
  row("design error norm", full_g(d.design_error_norm), full_g(s.design_error_norm));
  row("structural RMS (deg)", four_decimals(in_degrees(d.structural_error_rms)), four_decimals(in_degrees(s.structural_error_rms)));
  row("structural max (deg)", four_decimals(in_degrees(d.structural_error_max)), four_decimals(in_degrees(s.structural_error_max)));
  auto grashof = [](const LinkageSolution& x) { return x.check ? std::string(to_string(x.check->grashof)) : "-"; };
  row("Grashof type", grashof(d), grashof(s));
  auto transmission = [](const LinkageSolution& x) {
    return x.check ? four_decimals(in_degrees(x.check->transmission.min)) + " .. " + four_decimals(in_degrees(x.check->transmission.max)) : "-";
  };
  row("transmission angle (deg)", transmission(d), transmission(s));
  auto defect = [](const LinkageSolution& x) {
    return x.check ? std::string(x.check->branch_defect ? "YES" : "no") : "-";
  };
  row("branch defect", defect(d), defect(s));
  if (s.check && s.check->branch_defect) out << "branch defect: " << s.check->branch_defect_reason << "\n";
  if (positions) {
    // Angle changes from each solution's own dial zeros, so that fitted zeros compare directly.
    out << "\n";
    std::snprintf(line, sizeof line, "%14s %14s %18s %18s %14s %14s\n", "dpsi (deg)", "dphi (deg)",
                  "dphi design", "dphi structural", "s design", "s structural");
    out << line;
    auto error = [&](const LinkageSolution& x, Eigen::Index i) -> double {
      if (x.phi_generated.size() == 0) return std::nan("");
      return in_degrees(wrap_angle(p.pairs.delta_phi(i) - (x.phi_generated(i) - x.dial_zeros.beta)));
    };
    for (Eigen::Index i = 0; i < p.pairs.delta_psi.size(); ++i) {
      const double dphi = in_degrees(p.pairs.delta_phi(i)), sd = error(d, i), ss = error(s, i);
      std::snprintf(line, sizeof line, "%14.4f %14.4f %18.4f %18.4f %14.6f %14.6f\n", in_degrees(p.pairs.delta_psi(i)),
                    dphi, dphi - sd, dphi - ss, sd, ss);
      out << line;
    }
  }
  return out.str();
}

}  // namespace

std::string to_json(const SynthesisRun& run) { return synthesis_json(run.result, run).dump(2) + "\n"; }

std::string report(const SynthesisRun& run, bool positions) { return synthesis_text(run.result, run, positions); }

}  // namespace spdfit::linkage
