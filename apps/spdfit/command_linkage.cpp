// spdfit linkage synthesize ... / spdfit linkage analyze ...: four-bar function generators.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "linkage_arguments.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/synthesis.hpp"

namespace spdfit::cli {

using namespace spdfit::linkage;

namespace {

struct SynthesizeOptionsCli {
  std::string pairs, weights, output;
  bool radians = false, steering = false, fit_dial_zeros = false, json = false, positions = false;
  std::optional<double> rho, alpha, beta;
  std::string function, x_range, psi_range, phi_range, spacing = "uniform";
  int points = 21;
  double tolerance = 1e-10, threshold = -1.0;
  int max_iterations = 100;
};

struct AnalyzeOptionsCli {
  std::string lengths, psi_range = "0:360", output;
  int points = 37;
  bool json = false;
};

std::string g(double value) {
  if (std::isnan(value)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string f4(double value) {
  if (std::isnan(value)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

// ---- synthesize: input -----------------------------------------------------------------------

struct Prescribed {
  PrescribedPairs pairs;   // radians
  Eigen::VectorXd weights;
  std::string source;      // for the report
};

Prescribed load_pairs(const SynthesizeOptionsCli& o) {
  Prescribed p;
  const io::Table table = io::read_table(o.pairs);
  if (table.values.cols() != 2) {
    throw io::DataError(o.pairs, 0, 0,
                        "the pairs file has " + std::to_string(table.values.cols()) +
                            " columns: two are needed, the input angle psi and the output angle phi");
  }
  const Eigen::Index needed = o.fit_dial_zeros ? 5 : 3;
  if (table.values.rows() < needed) {
    throw io::DataError(o.pairs, 0, 0,
                        std::to_string(table.values.rows()) + " pair(s): at least " + std::to_string(needed) +
                            " are needed (" + std::to_string(needed) + " give exact precision-point synthesis" +
                            (o.fit_dial_zeros ? " with dial zeros)" : ")"));
  }
  const double scale = o.radians ? 1.0 : kRadiansPerDegree;
  p.pairs.delta_psi = table.values.col(0) * scale;
  p.pairs.delta_phi = table.values.col(1) * scale;
  p.source = o.pairs;
  return p;
}

Eigen::VectorXd load_weights(const std::string& path, Eigen::Index m) {
  const Eigen::MatrixXd W = io::read_matrix(path);
  if (W.size() != m || (W.rows() != 1 && W.cols() != 1)) {
    throw io::DataError(path, 0, 0,
                        "the weights are " + std::to_string(W.rows()) + "x" + std::to_string(W.cols()) +
                            ": one column of " + std::to_string(m) + " weights (one per pair) is needed");
  }
  Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(W.data(), m);
  for (Eigen::Index i = 0; i < m; ++i) {
    if (!(w(i) > 0.0)) {
      throw io::DataError(path, 0, 0, "weight " + std::to_string(i + 1) + " is " + io::format_double(w(i)) +
                                          ": weights must be positive");
    }
  }
  return w;
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
    if (!o.weights.empty()) p.weights = load_weights(o.weights, p.pairs.delta_psi.size());
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
  if (!o.weights.empty()) p.weights = load_weights(o.weights, p.pairs.delta_psi.size());
  return p;
}

// ---- synthesize: output ----------------------------------------------------------------------

nlohmann::json range_json(const AngleRange& range) {
  return {{"min", degrees(range.min)}, {"max", degrees(range.max)}};
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
  out["warnings"] = r.warnings;
  return out;
}

std::string synthesis_text(const SynthesisResult& r, const Prescribed& p, bool positions) {
  std::ostringstream out;
  const LinkageSolution& d = r.design;
  const LinkageSolution& s = r.structural;
  out << "Four-bar function generator, " << r.positions << " prescribed positions: " << p.source
      << (p.weights.size() ? ", weighted" : "") << "\n";
  out << "synthesis matrix S: condition number " << g(r.condition_number) << ", rank " << r.rank
      << (r.used_svd ? " (edited SVD)" : " (Householder QR)") << (r.precision_point ? "; precision points: exact" : "")
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

void run_synthesize(const SynthesizeOptionsCli& o, const GlobalOptions& global) {
  SynthesisOptions options;
  options.fit_dial_zeros = o.fit_dial_zeros;
  options.gauss_newton.tolerance = o.tolerance;
  options.gauss_newton.max_iterations = o.max_iterations;
  options.threshold = o.threshold;
  options.gauss_newton.threshold = o.threshold;
  const Prescribed p = prescribe(o, options);
  const SynthesisResult r = synthesize(p.pairs.delta_psi, p.pairs.delta_phi, p.weights, options);
  for (const std::string& w : r.warnings) warn(global, w);
  if (!r.ok()) throw DataFailure(r.message);
  emit(o.json ? synthesis_json(r, p).dump(2) + "\n" : synthesis_text(r, p, o.positions), o.output);
}

// ---- analyze ---------------------------------------------------------------------------------

nlohmann::json optional_degrees(const std::optional<double>& x) {
  return x ? nlohmann::json(degrees(*x)) : nlohmann::json(nullptr);
}

void run_analyze(const AnalyzeOptionsCli& o) {
  const std::vector<double> a = parse_list(o.lengths, 4, "--lengths");
  for (double x : a) {
    if (!(x > 0.0)) throw UsageError("--lengths must all be positive");
  }
  const FourBar bar{a[0], a[1], a[2], a[3]};
  const auto [lo, hi] = parse_range(o.psi_range, "--psi-range");
  if (!(lo < hi)) throw UsageError("--psi-range must have LO < HI");
  if (o.points < 2) throw UsageError("--points must be at least 2");
  const Analysis r = analyze(bar, spaced_points(radians(lo), radians(hi), o.points, Spacing::Uniform));

  if (o.json) {
    nlohmann::json out;
    out["lengths"] = {{"a1", bar.a1}, {"a2", bar.a2}, {"a3", bar.a3}, {"a4", bar.a4}};
    out["k"] = vector_json(r.k);
    out["grashof"] = to_string(r.grashof);
    out["input_fully_rotates"] = r.input_fully_rotates;
    nlohmann::json dead = nlohmann::json::array();
    for (double d : r.dead_points) dead.push_back(degrees(d));
    out["dead_points_deg"] = dead;
    out["transmission_angle_deg"] = r.transmission ? range_json(*r.transmission) : nlohmann::json(nullptr);
    nlohmann::json samples = nlohmann::json::array();
    for (const AnalysisSample& s : r.samples) {
      samples.push_back({{"psi_deg", degrees(s.psi)},
                         {"phi_plus_deg", optional_degrees(s.phi_plus)},
                         {"phi_minus_deg", optional_degrees(s.phi_minus)},
                         {"transmission_angle_deg", optional_degrees(s.transmission_angle)}});
    }
    out["samples"] = samples;
    emit(out.dump(2) + "\n", o.output);
    return;
  }
  std::ostringstream out;
  out << "four-bar a1 = " << g(bar.a1) << " (ground), a2 = " << g(bar.a2) << " (input), a3 = " << g(bar.a3)
      << " (coupler), a4 = " << g(bar.a4) << " (output)\n";
  out << "Freudenstein parameters k = [" << g(r.k(0)) << ", " << g(r.k(1)) << ", " << g(r.k(2)) << "]\n";
  out << "Grashof type: " << to_string(r.grashof) << "; the input "
      << (r.input_fully_rotates ? "turns fully" : "cannot turn fully") << "\n";
  out << "dead points (input angle, deg):";
  if (r.dead_points.empty()) out << " none";
  for (double d : r.dead_points) out << " " << f4(degrees(d));
  out << "\ntransmission angle over the range (deg): "
      << (r.transmission ? f4(degrees(r.transmission->min)) + " .. " + f4(degrees(r.transmission->max))
                         : std::string("- (cannot be assembled)"))
      << "\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%12s %16s %16s %20s\n", "psi (deg)", "phi branch +1", "phi branch -1",
                "transmission (deg)");
  out << line;
  auto cell = [](const std::optional<double>& x) { return x ? f4(degrees(*x)) : std::string("-"); };
  for (const AnalysisSample& s : r.samples) {
    std::snprintf(line, sizeof line, "%12.4f %16s %16s %20s\n", degrees(s.psi), cell(s.phi_plus).c_str(),
                  cell(s.phi_minus).c_str(), cell(s.transmission_angle).c_str());
    out << line;
  }
  emit(out.str(), o.output);
}

}  // namespace

Command add_linkage_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* linkage = app.add_subcommand("linkage", "Four-bar function generators: synthesize from pairs, analyze");
  linkage->require_subcommand(1);

  auto so = std::make_shared<SynthesizeOptionsCli>();
  CLI::App* syn = linkage->add_subcommand(
      "synthesize", "Synthesize a four-bar function generator (Freudenstein): design error, then structural error");
  syn->add_option("--pairs", so->pairs, "File of input-output pairs: columns psi, phi (degrees; a header row allowed)");
  syn->add_option("--weights", so->weights, "File of one positive weight per pair (W in 1/2 d^T W d)");
  syn->add_flag("--radians", so->radians, "The --pairs angles are in radians");
  syn->add_flag("--steering", so->steering, "Prescribe the steering condition (eq. 3.5); needs --rho");
  syn->add_option("--rho", so->rho, "Steering: track / wheelbase (e.g. 0.5)");
  syn->add_option("--function", so->function, "Prescribe y = f(x): linear, square, cube, sqrt, reciprocal, exp, ln, "
                                               "log10, sin, cos, tan")
      ->check(CLI::IsMember(function_names()));
  syn->add_option("--x-range", so->x_range, "--function: the x range LO:HI");
  syn->add_option("--psi-range", so->psi_range,
                  "Input angle changes LO:HI (degrees) from the dial zero (--steering default -30:30)");
  syn->add_option("--phi-range", so->phi_range, "--function: output angle changes LO:HI (degrees)");
  syn->add_option("--points", so->points, "Number of prescribed positions (default 21)");
  syn->add_option("--spacing", so->spacing, "Input spacing: uniform (default) or chebyshev")
      ->check(CLI::IsMember({"uniform", "chebyshev"}));
  syn->add_option("--alpha", so->alpha,
                  "Input dial zero (degrees): psi = alpha + delta psi (default 0; --steering: 90 - atan(rho/2))");
  syn->add_option("--beta", so->beta,
                  "Output dial zero (degrees): phi = beta + delta phi (default 0; --steering: 90 + atan(rho/2))");
  syn->add_flag("--fit-dial-zeros", so->fit_dial_zeros,
                "Also solve for alpha and beta (eq. 3.7); --alpha/--beta are then the start");
  syn->add_option("--tolerance", so->tolerance, "Gauss-Newton stops when ||Delta k|| < this (default 1e-10)")
      ->check(CLI::PositiveNumber);
  syn->add_option("--max-iterations", so->max_iterations, "Gauss-Newton iteration limit (default 100)")
      ->check(CLI::PositiveNumber);
  syn->add_option("--threshold", so->threshold,
                  "Relative singular-value cut-off for S (default max(m,3)*eps, notes 3.8)")
      ->check(CLI::Range(0.0, 1.0));
  syn->add_flag("--positions", so->positions, "Also print every position: prescribed and generated phi");
  syn->add_flag("--json", so->json, "Print the result as JSON");
  syn->add_option("-o,--output", so->output, "Write to FILE instead of stdout");

  auto ao = std::make_shared<AnalyzeOptionsCli>();
  CLI::App* ana = linkage->add_subcommand(
      "analyze", "Output angle on both assembly branches, transmission angle and dead points of a four-bar");
  ana->add_option("--lengths", ao->lengths, "a1,a2,a3,a4: ground, input, coupler, output")->required();
  ana->add_option("--psi-range", ao->psi_range, "Input angles LO:HI in degrees (default 0:360)");
  ana->add_option("--points", ao->points, "Number of input angles (default 37)");
  ana->add_flag("--json", ao->json, "Print the analysis as JSON");
  ana->add_option("-o,--output", ao->output, "Write to FILE instead of stdout");

  auto run = [so, ao, syn, ana, &global]() {
    if (so->threshold >= 1.0) throw UsageError("--threshold must be below 1");
    if (syn->parsed()) run_synthesize(*so, global);
    if (ana->parsed()) run_analyze(*ao);
  };
  return {linkage, run};
}

}  // namespace spdfit::cli
