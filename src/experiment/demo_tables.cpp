#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "experiment/demo_report.hpp"
#include "render/experiment_render.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"

namespace spdfit::experiment::demo {

using experiment::EntryExperimentResult;
using experiment::PairedComparison;
using experiment::ThesisExperimentResult;

const std::vector<Method>& beyond_estimators() {
  static const std::vector<Method> methods = [] {
    std::vector<Method> out;
    for (Method method : beyond_methods()) {
      if (method != Method::Auto) out.push_back(method);
    }
    return out;
  }();
  return methods;
}

const std::vector<double>& levels_2x2() {
  static const std::vector<double> levels = {0.0, 0.5, 1.0, 1.5, 1.9};
  return levels;
}

const std::vector<Eigen::Index>& sample_sizes() {
  static const std::vector<Eigen::Index> sizes = {100, 1000};
  return sizes;
}

const std::vector<double>& beyond_widths() {
  static const std::vector<double> widths = {1.0, 3.2};
  return widths;
}

const std::vector<Eigen::Index>& beyond_sizes() {
  static const std::vector<Eigen::Index> sizes = {12, 30, 100, 1000};
  return sizes;
}

const std::vector<Method>& beyond_methods() {
  static const std::vector<Method> methods = {Method::SymmetricProcrustes, Method::TotalLeastSquaresSymmetric,
                                              Method::Spde,                Method::SpdTotalLeastSquares,
                                              Method::PsdLeastSquares,     Method::Auto};
  return methods;
}

std::string percent(double fraction) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%.0f%%", 100.0 * fraction);
  return buffer;
}

std::string wrap(const std::string& text, const std::string& first, const std::string& rest) {
  std::istringstream words(text);
  std::string word, out, line = first;
  bool empty = true;
  while (words >> word) {
    if (!empty && line.size() + 1 + word.size() > kWidth) {
      out += line + '\n';
      line = rest;
      empty = true;
    }
    line += (empty ? "" : " ") + word;
    empty = false;
  }
  return out + line + '\n';
}

std::string bullet(const std::string& text) { return wrap(text, "* ", "  "); }

namespace {

std::string section_model() {
  const hexapod::Geometry geometry = hexapod::cubic_geometry();
  const hexapod::Matrix6d Mp = hexapod::joint_space_mass_matrix(geometry);
  const double gap = (Mp - hexapod::thesis_mass_matrix()).cwiseAbs().maxCoeff();
  const hexapod::Vector6d modes = hexapod::modal_frequencies_hz(geometry);
  std::ostringstream text;
  text << "The built-in cubic-configuration hexapod (payload " << format_fixed(geometry.payload_mass, 2)
       << " kg, struts on six edges of a " << format_number(hexapod::CubicGeometryParameters{}.edge)
       << " m cube) has the joint-space mass-inertia matrix M_p = J^-T M_x J^-1 + M_s of thesis eq. 2.12. It "
       << "differs from the UW hexapod's M_p, eq. 6.1, by at most " << format_number(gap)
       << " kg in any entry. With strut "
       << "stiffness " << format_fixed(geometry.strut_stiffness(0), 0)
       << " N/m its modes sqrt(eig(M_p^-1 K)) / 2 pi are";
  for (int i = 0; i < 6; ++i) text << (i ? ", " : " ") << format_fixed(modes(i), 2);
  text << " Hz. The experiments below use eq. 6.1 as the truth, like the thesis.";
  std::ostringstream out;
  out << "== 1. The hexapod (thesis ch. 2)\n\n" << wrap(text.str()) << '\n';
  return out.str();
}

std::string section_thesis(const std::vector<ThesisExperimentResult>& results, std::uint64_t seed) {
  std::ostringstream out;
  char line[256];
  out << "== 2. The thesis' experiments (000, ch. 6): M_p of eq. 6.1, m = 12 samples, uniform noise of\n"
      << "variance V in every entry of the accelerations A and the forces B\n\n";

  // One run shown in full, like the thesis' tables: Experiment 2, trial 0.
  const ThesisExperimentResult& shown = results[1];
  Random random(trial_seed(seed, 0));
  const hexapod::Measurements data = hexapod::simulate(shown.options.truth, shown.options.simulation, random);
  hexapod::IdentifyOptions identify_options;
  identify_options.truth = shown.options.truth;
  const std::vector<hexapod::MethodIdentification> run = hexapod::identify(data.A, data.B, identify_options);
  std::vector<std::string> titles = {"truth (eq. 6.1)"};
  std::vector<Eigen::MatrixXd> matrices = {shown.options.truth};
  for (const hexapod::MethodIdentification& m : run) {
    const Method method = m.result.method;
    if (m.result.ok() && (method == Method::SymmetricProcrustes ||
                          method == Method::TotalLeastSquaresSymmetric || method == Method::Spde)) {
      titles.push_back(std::string(to_string(method)) + " (error " + format_fixed(*m.error_vs_truth) + ")");
      matrices.push_back(m.result.X);
    }
  }
  out << "One run of Experiment 2 (V = " << shown.options.simulation.noise_var << "), as in the thesis' "
      << "eq. 6.11-6.16:\n\n"
      << format_side_by_side(titles, matrices, 4, kWidth + 12);

  out << "One run of each experiment, error ||M_p - M_hat||_F (our trial 0 | the thesis' single run):\n\n";
  std::snprintf(line, sizeof line, "%-4s %6s   %10s %10s %10s   |  %10s %10s %10s\n", "exp", "V",
                "procrustes", "tls-sym", "spde", "procrustes", "tls-sym", "spde");
  out << line;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ThesisExperimentResult& r = results[i];
    const experiment::ThesisReportedRun& thesis = experiment::kThesisReportedRuns[i];
    std::snprintf(
        line, sizeof line, "%-4d %6.3f   %10s %10s %10s   |  %10.4f %10.4f %10.4f\n", thesis.experiment,
        r.options.simulation.noise_var, format_fixed(r.of(Method::SymmetricProcrustes).errors[0]).c_str(),
        format_fixed(r.of(Method::TotalLeastSquaresSymmetric).errors[0]).c_str(),
        format_fixed(r.of(Method::Spde).errors[0]).c_str(), thesis.procrustes, thesis.tls_sym, thesis.spde);
    out << line;
  }

  out << "\nMonte Carlo: the same experiments repeated " << results.front().trials
      << " times each; mean error (standard error below)\n\n";
  std::snprintf(line, sizeof line, "%-4s %6s", "exp", "V");
  out << line;
  for (Method method : kSourceDocumentMethods) {
    std::snprintf(line, sizeof line, " %10s", std::string(to_string(method)).c_str());
    out << line;
  }
  out << "   spde beats procrustes\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ThesisExperimentResult& r = results[i];
    std::snprintf(line, sizeof line, "%-4d %6.3f", experiment::kThesisReportedRuns[i].experiment,
                  r.options.simulation.noise_var);
    std::string means = line, errors(means.size(), ' ');
    for (Method method : kSourceDocumentMethods) {
      const experiment::Summary& s = r.of(method).summary;
      std::snprintf(line, sizeof line, " %10s", format_fixed(s.mean, 3).c_str());
      means += line;
      std::snprintf(line, sizeof line, " %10s", ("(" + format_fixed(s.standard_error(), 3) + ")").c_str());
      errors += line;
    }
    const PairedComparison c = r.compare(Method::Spde, Method::SymmetricProcrustes);
    out << means << "   in " << percent(c.fraction_lower) << " of the trials\n" << errors << '\n';
  }
  out << '\n';
  return out.str();
}

std::string section_2x2(const std::vector<EntryExperimentResult>& results) {
  std::ostringstream out;
  out << "== 3. The paper's 2x2 example (001, Fig. 3): X = [3 1; 1 1] from (A0 + Va) X ~= A0 X + Vb,\n"
      << "Gaussian noise of std_a in A and std_b = 1 in B; " << results.front().trials
      << " trials per level\n\n"
      << detail::sweep_table(levels_2x2(), results) << '\n';
  return out.str();
}

std::string section_samples(const std::vector<ThesisExperimentResult>& thesis,
                            const std::vector<ThesisExperimentResult>& samples) {
  std::ostringstream out;
  char line[200];
  out << "== 4. More samples: Experiment 2's noise (V = " << format_number(thesis[1].options.simulation.noise_var)
      << ") with m = 12, " << sample_sizes()[0] << " and " << sample_sizes()[1] << " samples\n\n";
  std::snprintf(line, sizeof line, "%6s %8s", "m", "trials");
  out << line;
  for (Method method : {Method::SymmetricProcrustes, Method::TotalLeastSquaresSymmetric, Method::Spde}) {
    std::snprintf(line, sizeof line, " %18s", std::string(to_string(method)).c_str());
    out << line;
  }
  out << "   (mean error +- s.e.)\n";
  std::vector<const ThesisExperimentResult*> rows = {&thesis[1]};
  for (const ThesisExperimentResult& r : samples) rows.push_back(&r);
  for (const ThesisExperimentResult* r : rows) {
    std::snprintf(line, sizeof line, "%6ld %8zu", static_cast<long>(r->options.simulation.samples),
                  r->trials);
    out << line;
    for (Method method : {Method::SymmetricProcrustes, Method::TotalLeastSquaresSymmetric, Method::Spde}) {
      const experiment::Summary& s = r->of(method).summary;
      std::snprintf(line, sizeof line, " %9s +- %5s", format_fixed(s.mean, 3).c_str(),
                    format_fixed(s.standard_error(), 3).c_str());
      out << line;
    }
    out << '\n';
  }
  out << '\n';
  return out.str();
}

std::string section_beyond(const std::vector<ThesisExperimentResult>& beyond) {
  std::ostringstream out;
  char line[200];
  out << "== 5. Beyond the thesis: which method for how many samples. The thesis model with uniform noise\n"
      << "of width nm in A and B (variance nm^2/12); mean error ||M_p - M_hat||_F over "
      << beyond.front().trials << " trials; * marks the\nlowest mean, auto/best is auto's mean over it\n\n";
  std::snprintf(line, sizeof line, "%5s %6s", "nm", "m");
  out << line;
  for (Method method : beyond_methods()) {
    std::snprintf(line, sizeof line, " %11s", std::string(to_string(method)).c_str());
    out << line;
  }
  out << "   auto/best\n";
  for (const ThesisExperimentResult& r : beyond) {
    const double width = std::sqrt(12.0 * r.options.simulation.noise_var);
    std::snprintf(line, sizeof line, "%5s %6ld", format_number(width).c_str(),
                  static_cast<long>(r.options.simulation.samples));
    out << line;
    const double best = r.of(r.best_of(beyond_estimators())).summary.mean;
    for (Method method : beyond_methods()) {
      const double mean = r.of(method).summary.mean;
      const bool lowest = method != Method::Auto && mean == best;
      std::snprintf(line, sizeof line, " %11s", (format_fixed(mean, 3) + (lowest ? "*" : " ")).c_str());
      out << line;
    }
    std::snprintf(line, sizeof line, "   %9s\n", format_fixed(r.of(Method::Auto).summary.mean / best, 3).c_str());
    out << line;
  }
  out << '\n';
  return out.str();
}

std::string section_physical(const std::optional<experiment::PhysicalExperimentResult>& physical) {
  if (!physical) return "";
  return "== 6. Beyond M_p: the payload itself. With the geometry known, M_p has only the payload's mass,\n"
         "centre of mass and inertia (`spdfit hexapod identify --physical`); fitting those, physically\n"
         "consistent, against the generic estimates of M_p (`spdfit experiment physical`)\n\n" +
         experiment::report(*physical) + "\n";
}

// The standard deviations of a side, "0.2, 0.4, 0.8, ...".
std::string deviations(const Eigen::VectorXd& s) {
  std::string text;
  for (Eigen::Index i = 0; i < s.size(); ++i) text += (i == 0 ? "" : ", ") + format_number(s(i));
  return text;
}

std::string section_units(const ThesisExperimentResult& r) {
  std::ostringstream out;
  const hexapod::SimulationOptions& s = r.options.simulation;
  out << wrap("== 7. Units and noise. The thesis model with Gaussian noise of each sensor's own standard "
              "deviation (A: " + deviations(*s.noise_std_a) + "; B: " + deviations(*s.noise_std_b) +
              " N), forces written in kN, m = " + std::to_string(s.samples) + ", and " +
              std::to_string(s.rest_samples) + " rows recorded at rest; mean error ||M_p - M_hat||_F in N "
              "over " + std::to_string(r.trials) + " trials, without a noise model (equal noise assumed in "
              "every column, in the units given) and with the rest rows' covariances (--rest-a, --rest-b)")
      << "\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-9s %22s %22s\n", "method", "equal noise assumed", "rest segment");
  out << line;
  for (Method method : r.options.methods) {
    std::snprintf(line, sizeof line, "%-9s %22s %22s\n", std::string(to_string(method)).c_str(),
                  format_fixed(r.of(method, experiment::FitNoise::None).summary.mean, 3).c_str(),
                  format_fixed(r.of(method, experiment::FitNoise::Rest).summary.mean, 3).c_str());
    out << line;
  }
  out << '\n';
  return out.str();
}

}  // namespace

const std::vector<Eigen::Index>& physical_sizes() {
  static const std::vector<Eigen::Index> sizes{12, 100, 1000};
  return sizes;
}

experiment::ThesisExperimentOptions units_options() {
  experiment::ThesisExperimentOptions options;
  hexapod::SimulationOptions& s = options.simulation;
  s.samples = 1000;
  s.distribution = hexapod::NoiseDistribution::Gaussian;
  s.noise_std_a = (Eigen::VectorXd(6) << 0.2, 0.4, 0.8, 0.2, 0.4, 0.8).finished();
  s.noise_std_b = (Eigen::VectorXd(6) << 3.0, 1.0, 0.3, 3.0, 1.0, 0.3).finished();
  s.rest_samples = 2000;
  s.scale_b = 1e-3;  // newtons to kilonewtons
  options.methods = {Method::Auto, Method::SpdTotalLeastSquares};
  options.noise_models = {experiment::FitNoise::None, experiment::FitNoise::Rest};
  return options;
}

std::string tables(const Results& results) {
  return section_model() + section_thesis(results.thesis, results.seed) + section_2x2(results.paper) +
         section_samples(results.thesis, results.samples) + section_beyond(results.beyond) +
         section_physical(results.physical) + section_units(results.units);
}

}  // namespace spdfit::experiment::demo
