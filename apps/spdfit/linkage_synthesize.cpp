// spdfit linkage synthesize: prescribed positions in, a four-bar function generator out.
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "cli.hpp"
#include "linkage_arguments.hpp"
#include "linkage_commands.hpp"
#include "output.hpp"
#include "spdfit/linkage/pairs_file.hpp"
#include "spdfit/linkage/synthesis.hpp"

namespace spdfit::cli {

using namespace spdfit::linkage;

namespace {

struct Prescribed {
  PrescribedPairs pairs;   // radians
  Eigen::VectorXd weights;
  std::string source;      // for the report
};

Prescribed load_pairs(const SynthesizeOptionsCli& o) {
  PairsFileOptions options;
  options.radians = o.radians;
  options.min_pairs = o.fit_dial_zeros ? 5 : 3;
  Prescribed p;
  p.pairs = read_pairs(o.pairs, options);
  p.source = o.pairs;
  return p;
}

Spacing parse_spacing(const std::string& name) { return name == "chebyshev" ? Spacing::Chebyshev : Spacing::Uniform; }

Prescribed prescribe(const SynthesizeOptionsCli& o, SynthesisOptions& options) {
  const int sources = !o.pairs.empty() + o.steering + !o.function.empty();
  if (sources != 1) throw UsageError("give exactly one of --pairs FILE, --steering or --function NAME");
  const bool generated = o.pairs.empty();
  if (!generated && (o.points != 21 || o.spacing != "uniform" || !o.psi_range.empty() || !o.phi_range.empty() ||
                     !o.x_range.empty())) {
    throw UsageError("--points, --spacing, --x-range, --psi-range and --phi-range describe a prescribed function; "
                     "they do not apply to --pairs");
  }
  if (o.radians && generated) throw UsageError("--radians applies to the angles of a --pairs file");
  if (o.rho && !o.steering) throw UsageError("--rho applies to --steering");
  if (o.points < 1) throw UsageError("--points must be at least 1");
  options.alpha = o.alpha ? std::optional<double>(radians(*o.alpha)) : std::nullopt;
  options.beta = o.beta ? std::optional<double>(radians(*o.beta)) : std::nullopt;

  Prescribed p;
  if (!generated) {
    p = load_pairs(o);
    if (!o.weights.empty()) p.weights = read_weights(o.weights, p.pairs.delta_psi.size());
    return p;
  }
  const Spacing spacing = parse_spacing(o.spacing);
  if (o.steering) {
    if (!o.rho) throw UsageError("--steering needs --rho (track / wheelbase, e.g. 0.5)");
    if (!o.phi_range.empty() || !o.x_range.empty()) {
      throw UsageError("--steering takes --psi-range only: the output follows from the steering condition");
    }
    const auto [lo, hi] = o.psi_range.empty() ? std::make_pair(-30.0, 30.0) : parse_range(o.psi_range, "--psi-range");
    if (!(lo < hi)) throw UsageError("--psi-range must have LO < HI");
    p.pairs = steering_pairs(*o.rho, radians(lo), radians(hi), o.points, spacing);
    if (!o.fit_dial_zeros && !o.alpha && !o.beta) {
      const DialZeros zeros = trapezoid_dial_zeros(*o.rho);
      options.alpha = zeros.alpha;
      options.beta = zeros.beta;
    }
    p.source = "steering condition (eq. 3.5), rho = " + g(*o.rho);
  } else {
    if (o.x_range.empty() || o.psi_range.empty() || o.phi_range.empty()) {
      throw UsageError("--function needs --x-range, --psi-range and --phi-range");
    }
    const auto [x_lo, x_hi] = parse_range(o.x_range, "--x-range");
    const auto [psi_lo, psi_hi] = parse_range(o.psi_range, "--psi-range");
    const auto [phi_lo, phi_hi] = parse_range(o.phi_range, "--phi-range");
    if (!(x_lo < x_hi)) throw UsageError("--x-range must have LO < HI");
    try {
      p.pairs = function_pairs(o.function, x_lo, x_hi, radians(psi_lo), radians(psi_hi), radians(phi_lo),
                               radians(phi_hi), o.points, spacing);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--function: ") + e.what());
    }
    p.source = "y = " + o.function + "(x), x in [" + g(x_lo) + ", " + g(x_hi) + "]";
  }
  if (!o.weights.empty()) p.weights = read_weights(o.weights, p.pairs.delta_psi.size());
  return p;
}

nlohmann::json degrees_json(const Eigen::VectorXd& v) { return vector_json(v / kRadiansPerDegree); }

nlohmann::json solution_json(const LinkageSolution& s, bool with_iterations) {
  nlohmann::json out;
  out["k"] = vector_json(s.k);
  if (s.lengths) {
    out["lengths"] = {{"a1", s.lengths->a1}, {"a2", s.lengths->a2}, {"a3", s.lengths->a3}, {"a4", s.lengths->a4}};
  } else {
    out["lengths"] = nullptr;
  }
  out["design_error_norm"] = number_json(s.design_error_norm);
  out["structural_error_rms_deg"] = number_json(degrees(s.structural_error_rms));
  out["structural_error_max_deg"] = number_json(degrees(s.structural_error_max));
  if (with_iterations) {
    out["iterations"] = s.iterations;
    out["final_step_norm"] = s.final_step_norm;
  }
  out["dial_zeros_deg"] = {{"alpha", degrees(s.dial_zeros.alpha)}, {"beta", degrees(s.dial_zeros.beta)}};
  out["phi_generated_deg"] = degrees_json(s.phi_generated);
  if (s.check) {
    out["grashof"] = to_string(s.check->grashof);
    out["transmission_angle_deg"] = range_json(s.check->transmission);
    out["branch_defect"] = s.check->branch_defect;
    out["branch_defect_reason"] = s.check->branch_defect_reason;
    out["dead_points_deg"] = vector_json(Eigen::Map<const Eigen::VectorXd>(s.check->dead_points.data(),
                                                                           s.check->dead_points.size()) /
                                         kRadiansPerDegree);
  }
  return out;
}

nlohmann::json synthesis_json(const SynthesisResult& r, const Prescribed& p) {
  nlohmann::json out;
  out["design"] = solution_json(r.design, false);
  out["structural"] = solution_json(r.structural, true);
  out["condition_number"] = number_json(r.condition_number);
  out["scaled_condition_number"] = number_json(r.scaled_condition_number);
  out["rank_decided_on"] = "column-scaled";
  const MotionCheck& check = *r.structural.check;
  out["grashof"] = to_string(check.grashof);
  out["transmission_angle_deg"] = range_json(check.transmission);
  out["branch_defect"] = check.branch_defect;
  out["m"] = r.positions;
  out["source"] = p.source;
  out["precision_point"] = r.precision_point;
  out["dial_zeros_fitted"] = r.dial_zeros_fitted;
  out["rank"] = r.rank;
  out["used_svd"] = r.used_svd;
  out["branch"] = r.branch;
  out["pairs"] = {{"psi_deg", degrees_json(r.psi)}, {"phi_deg", degrees_json(r.phi)}};
  out["weights"] = p.weights.size() ? vector_json(p.weights) : nlohmann::json(nullptr);
  out["warnings"] = texts(r.warnings);
  return out;
}

std::string synthesis_text(const SynthesisResult& r, const Prescribed& p, bool positions) {
  std::ostringstream out;
  const LinkageSolution& d = r.design;
  const LinkageSolution& s = r.structural;
  out << "Four-bar function generator, " << r.positions << " prescribed positions: " << p.source
      << (p.weights.size() ? ", weighted" : "") << "\n";
  out << "synthesis matrix S: condition number " << g(r.condition_number) << ", rank " << r.rank
      << (r.used_svd ? " (edited SVD, minimum norm)" : "") << " (column-scaled: condition number "
      << g(r.scaled_condition_number) << ")" << (r.precision_point ? "; precision points: exact" : "")
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
  for (int i = 0; i < 3; ++i) row(i == 0 ? "k1" : (i == 1 ? "k2" : "k3"), g(d.k(i)), g(s.k(i)));
  auto length = [](const LinkageSolution& x, int i) {
    if (!x.lengths) return std::string("-");
    const double a[4] = {x.lengths->a1, x.lengths->a2, x.lengths->a3, x.lengths->a4};
    return g(a[i]);
  };
  const char* names[4] = {"a1 (ground)", "a2 (input)", "a3 (coupler)", "a4 (output)"};
  for (int i = 0; i < 4; ++i) row(names[i], length(d, i), length(s, i));
  row("alpha, beta (deg)", f4(degrees(d.dial_zeros.alpha)) + ", " + f4(degrees(d.dial_zeros.beta)),
      f4(degrees(s.dial_zeros.alpha)) + ", " + f4(degrees(s.dial_zeros.beta)));
  row("design error norm", g(d.design_error_norm), g(s.design_error_norm));
  row("structural RMS (deg)", f4(degrees(d.structural_error_rms)), f4(degrees(s.structural_error_rms)));
  row("structural max (deg)", f4(degrees(d.structural_error_max)), f4(degrees(s.structural_error_max)));
  auto grashof = [](const LinkageSolution& x) { return x.check ? std::string(to_string(x.check->grashof)) : "-"; };
  row("Grashof type", grashof(d), grashof(s));
  auto transmission = [](const LinkageSolution& x) {
    return x.check ? f4(degrees(x.check->transmission.min)) + " .. " + f4(degrees(x.check->transmission.max)) : "-";
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
      return degrees(wrap_angle(p.pairs.delta_phi(i) - (x.phi_generated(i) - x.dial_zeros.beta)));
    };
    for (Eigen::Index i = 0; i < p.pairs.delta_psi.size(); ++i) {
      const double dphi = degrees(p.pairs.delta_phi(i)), sd = error(d, i), ss = error(s, i);
      std::snprintf(line, sizeof line, "%14.4f %14.4f %18.4f %18.4f %14.6f %14.6f\n", degrees(p.pairs.delta_psi(i)),
                    dphi, dphi - sd, dphi - ss, sd, ss);
      out << line;
    }
  }
  return out.str();
}

}  // namespace

void run_synthesize(const SynthesizeOptionsCli& o, const GlobalOptions& global) {
  SynthesisOptions options;
  options.fit_dial_zeros = o.fit_dial_zeros;
  options.gauss_newton.tolerance = o.tolerance;
  options.gauss_newton.max_iterations = o.max_iterations;
  if (o.threshold >= 0.0) {
    options.rank_tolerance = o.threshold;
    options.gauss_newton.rank_tolerance = o.threshold;
  }
  const Prescribed p = prescribe(o, options);
  const SynthesisResult r = synthesize(p.pairs.delta_psi, p.pairs.delta_phi, p.weights, options);
  for (const auto& w : r.warnings) warn(global, w);
  if (!r.ok()) throw DataFailure(r.message);
  emit(o.json ? synthesis_json(r, p).dump(2) + "\n" : synthesis_text(r, p, o.positions), o.output);
}

}  // namespace spdfit::cli
