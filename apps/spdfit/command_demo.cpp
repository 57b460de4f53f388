// spdfit demo: the source documents' experiments on built-in data, and what they show.
//
// Every statement in the closing explanation is chosen by comparing the numbers just computed
// (paired differences and their standard errors); none is fixed text about which method wins.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "experiment_output.hpp"
#include "output.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"

namespace spdfit::cli {

namespace {

using experiment::compare_paired;
using experiment::EntryExperimentResult;
using experiment::PairedComparison;
using experiment::ThesisExperimentResult;

// A difference counts as real when it exceeds this many standard errors of the paired mean
// difference (a tie passes by chance with probability 0.3%).
constexpr double kSignificance = 3.0;

const std::vector<double> kDemoLevels = {0.0, 0.5, 1.0, 1.5, 1.9};
const char* const kEntryNames[] = {"x11", "x12", "x22"};

enum class Order { Lower, Tie, Higher };

Order order_of(const PairedComparison& c) {
  if (c.mean_difference + kSignificance * c.standard_error < 0) return Order::Lower;
  if (c.mean_difference - kSignificance * c.standard_error > 0) return Order::Higher;
  return Order::Tie;
}

std::string percent(double fraction) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%.0f%%", 100.0 * fraction);
  return buffer;
}

std::string trimmed(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

// `text` wrapped at kWidth columns, the first line starting with `first`, the others indented
// to match.
constexpr std::size_t kWidth = 98;
std::string wrap(const std::string& text, const std::string& first = "", const std::string& rest = "") {
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

std::vector<double> absolute_errors(const experiment::EntryStatistics& s, Eigen::Index entry) {
  std::vector<double> out(static_cast<std::size_t>(s.errors.rows()));
  for (Eigen::Index k = 0; k < s.errors.rows(); ++k) out[static_cast<std::size_t>(k)] = std::abs(s.errors(k, entry));
  return out;
}

// |e_spde| - |e_procrustes| for each entry, trial by trial.
std::vector<PairedComparison> spde_vs_procrustes(const EntryExperimentResult& r) {
  std::vector<PairedComparison> out;
  for (Eigen::Index e = 0; e < 3; ++e) {
    out.push_back(compare_paired(absolute_errors(r.of(Method::Spde), e),
                                 absolute_errors(r.of(Method::SymmetricProcrustes), e)));
  }
  return out;
}

std::string section_model() {
  const hexapod::Geometry geometry = hexapod::cubic_geometry();
  const hexapod::Matrix6d Mp = hexapod::joint_space_mass_matrix(geometry);
  const double gap = (Mp - hexapod::thesis_mass_matrix()).cwiseAbs().maxCoeff();
  const hexapod::Vector6d modes = hexapod::modal_frequencies_hz(geometry);
  std::ostringstream text;
  text << "The built-in cubic-configuration hexapod (payload " << fixed(geometry.payload_mass, 2)
       << " kg, struts on six edges of a " << trimmed(hexapod::CubicGeometryParameters{}.edge)
       << " m cube) has the joint-space mass-inertia matrix M_p = J^-T M_x J^-1 + M_s of thesis eq. 2.12. It "
       << "differs from the UW hexapod's M_p, eq. 6.1, by at most " << trimmed(gap) << " kg in any entry. With strut "
       << "stiffness " << fixed(geometry.strut_stiffness(0), 0) << " N/m its modes sqrt(eig(M_p^-1 K)) / 2 pi are";
  for (int i = 0; i < 6; ++i) text << (i ? ", " : " ") << fixed(modes(i), 2);
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
  const hexapod::Measurements data =
      hexapod::simulate(shown.options.truth, shown.options.simulation, random);
  hexapod::IdentifyOptions identify_options;
  identify_options.truth = shown.options.truth;
  const std::vector<hexapod::MethodIdentification> run = hexapod::identify(data.A, data.B, identify_options);
  std::vector<std::string> titles = {"truth (eq. 6.1)"};
  std::vector<Eigen::MatrixXd> matrices = {shown.options.truth};
  for (const hexapod::MethodIdentification& m : run) {
    const Method method = m.result.method;
    if (m.result.ok() &&
        (method == Method::SymmetricProcrustes || method == Method::TotalLeastSquaresSymmetric || method == Method::Spde)) {
      titles.push_back(std::string(to_string(method)) + " (error " + fixed(*m.error_vs_truth) + ")");
      matrices.push_back(m.result.X);
    }
  }
  out << "One run of Experiment 2 (V = " << shown.options.simulation.noise_var << "), as in the thesis' "
      << "eq. 6.11-6.16:\n\n"
      << side_by_side(titles, matrices, 4, kWidth + 12);

  out << "One run of each experiment, error ||M_p - M_hat||_F (our trial 0 | the thesis' single run):\n\n";
  std::snprintf(line, sizeof line, "%-4s %6s   %10s %10s %10s   |  %10s %10s %10s\n", "exp", "V", "procrustes",
                "tls-sym", "spde", "procrustes", "tls-sym", "spde");
  out << line;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ThesisExperimentResult& r = results[i];
    const experiment::ThesisReportedRun& thesis = experiment::kThesisReportedRuns[i];
    std::snprintf(line, sizeof line, "%-4d %6.3f   %10s %10s %10s   |  %10.4f %10.4f %10.4f\n", thesis.experiment,
                  r.options.simulation.noise_var, fixed(r.of(Method::SymmetricProcrustes).errors[0]).c_str(),
                  fixed(r.of(Method::TotalLeastSquaresSymmetric).errors[0]).c_str(),
                  fixed(r.of(Method::Spde).errors[0]).c_str(), thesis.procrustes, thesis.tls_sym, thesis.spde);
    out << line;
  }

  out << "\nMonte Carlo: the same experiments repeated " << results.front().trials
      << " times each; mean error (standard error below)\n\n";
  std::snprintf(line, sizeof line, "%-4s %6s", "exp", "V");
  out << line;
  for (Method method : kAllMethods) {
    std::snprintf(line, sizeof line, " %10s", std::string(to_string(method)).c_str());
    out << line;
  }
  out << "   spde beats procrustes\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ThesisExperimentResult& r = results[i];
    std::snprintf(line, sizeof line, "%-4d %6.3f", experiment::kThesisReportedRuns[i].experiment,
                  r.options.simulation.noise_var);
    std::string means = line, errors(means.size(), ' ');
    for (Method method : kAllMethods) {
      const experiment::Summary& s = r.of(method).summary;
      std::snprintf(line, sizeof line, " %10s", fixed(s.mean, 3).c_str());
      means += line;
      std::snprintf(line, sizeof line, " %10s", ("(" + fixed(s.standard_error(), 3) + ")").c_str());
      errors += line;
    }
    const PairedComparison c = compare_paired(r.of(Method::Spde).errors, r.of(Method::SymmetricProcrustes).errors);
    out << means << "   in " << percent(c.fraction_lower) << " of the trials\n" << errors << '\n';
  }
  out << '\n';
  return out.str();
}

std::string section_2x2(const std::vector<EntryExperimentResult>& results) {
  std::ostringstream out;
  out << "== 3. The paper's 2x2 example (001, Fig. 3): X = [3 1; 1 1] from (A0 + Va) X ~= A0 X + Vb,\n"
      << "Gaussian noise of std_a in A and std_b = 1 in B; " << results.front().trials << " trials per level\n\n"
      << sweep_table(kDemoLevels, results) << '\n';
  return out.str();
}

// Experiment 2's noise with more samples than the thesis' 12: `samples` holds the runs at
// kMoreSamples (the m = 12 run is thesis[1]).
const std::vector<Eigen::Index> kMoreSamples = {100, 1000};
const Method kCompared[] = {Method::SymmetricProcrustes, Method::TotalLeastSquaresSymmetric, Method::Spde};

std::string section_samples(const std::vector<ThesisExperimentResult>& thesis,
                            const std::vector<ThesisExperimentResult>& samples) {
  std::ostringstream out;
  char line[200];
  out << "== 4. More samples: Experiment 2's noise (V = " << trimmed(thesis[1].options.simulation.noise_var)
      << ") with m = 12, " << kMoreSamples[0] << " and " << kMoreSamples[1] << " samples\n\n";
  std::snprintf(line, sizeof line, "%6s %8s", "m", "trials");
  out << line;
  for (Method method : kCompared) {
    std::snprintf(line, sizeof line, " %18s", std::string(to_string(method)).c_str());
    out << line;
  }
  out << "   (mean error +- s.e.)\n";
  std::vector<const ThesisExperimentResult*> rows = {&thesis[1]};
  for (const ThesisExperimentResult& r : samples) rows.push_back(&r);
  for (const ThesisExperimentResult* r : rows) {
    std::snprintf(line, sizeof line, "%6ld %8zu", static_cast<long>(r->options.simulation.samples), r->trials);
    out << line;
    for (Method method : kCompared) {
      const experiment::Summary& s = r->of(method).summary;
      std::snprintf(line, sizeof line, " %9s +- %5s", fixed(s.mean, 3).c_str(), fixed(s.standard_error(), 3).c_str());
      out << line;
    }
    out << '\n';
  }
  out << '\n';
  return out.str();
}

// The method among kCompared with the smallest mean error.
Method best_of(const ThesisExperimentResult& r) {
  Method best = kCompared[0];
  for (Method method : kCompared) {
    if (r.of(method).summary.mean < r.of(best).summary.mean) best = method;
  }
  return best;
}

// The explanation, statement by statement, each chosen by the numbers.
std::string section_findings(const std::vector<ThesisExperimentResult>& thesis,
                             const std::vector<ThesisExperimentResult>& samples,
                             const std::vector<EntryExperimentResult>& paper) {
  std::ostringstream out;
  out << "== What the numbers show\n\n";

  // Thesis: SPDE against Procrustes at each level, trial by trial.
  std::vector<PairedComparison> c;
  for (const ThesisExperimentResult& r : thesis) {
    c.push_back(compare_paired(r.of(Method::Spde).errors, r.of(Method::SymmetricProcrustes).errors));
  }
  bool all_lower = true, growing = true;
  double previous_gain = -1, weakest = INFINITY;
  std::string gains, losses;
  for (std::size_t i = 0; i < thesis.size(); ++i) {
    const double procrustes = thesis[i].of(Method::SymmetricProcrustes).summary.mean;
    const double gain = -c[i].mean_difference / procrustes;
    all_lower = all_lower && order_of(c[i]) == Order::Lower;
    growing = growing && gain > previous_gain;
    previous_gain = gain;
    weakest = std::min(weakest, -c[i].mean_difference / c[i].standard_error);
    gains += std::string(i ? ", " : "") + percent(gain) + " at V = " + trimmed(thesis[i].options.simulation.noise_var);
    losses += std::string(i ? ", " : "") + percent(1.0 - c[i].fraction_lower);
  }
  std::string text;
  if (all_lower) {
    text = "Hexapod, thesis set-up: SPDE's mean error is below symmetric Procrustes' at all three noise levels, by " +
           gains + (growing ? ", growing with the noise" : "") + ". The smallest of these differences is " +
           fixed(weakest, 0) + " standard errors of the trial-by-trial difference: far beyond chance.";
  } else {
    text = "Hexapod, thesis set-up, SPDE against symmetric Procrustes:";
    for (std::size_t i = 0; i < thesis.size(); ++i) {
      const Order o = order_of(c[i]);
      text += std::string(i ? ";" : "") + " at V = " + trimmed(thesis[i].options.simulation.noise_var) + " " +
              (o == Order::Lower ? "SPDE's mean error is lower" :
               o == Order::Higher ? "SPDE's mean error is higher" : "no significant difference");
    }
    text += ".";
  }
  text += " Yet Procrustes is closer to the truth in " + losses +
          " of the single runs, so one run like the thesis' tables can show either order; the averages are what "
          "carries over to new data.";
  out << bullet(text);

  bool ls_worse = true;
  for (const ThesisExperimentResult& r : thesis) {
    ls_worse = ls_worse && order_of(compare_paired(r.of(Method::LeastSquares).errors,
                                                   r.of(Method::SymmetricProcrustes).errors)) == Order::Higher;
  }
  if (ls_worse) {
    out << bullet("Ignoring symmetry costs accuracy: unconstrained least squares (ls) is worse than Procrustes at "
                  "every level.");
  }
  const experiment::Summary& tls = thesis.back().of(Method::TotalLeastSquaresSymmetric).summary;
  const experiment::Summary& spde_high = thesis.back().of(Method::Spde).summary;
  if (tls.mean > 1.1 * tls.median && tls.max > 5.0 * tls.median) {
    out << bullet("TLS made symmetric (eq. 4.38) is erratic: at V = " +
                  trimmed(thesis.back().options.simulation.noise_var) + " its mean error " + trimmed(tls.mean) +
                  " is pulled far above its median " + trimmed(tls.median) + " by a few runs with errors up to " +
                  trimmed(tls.max) + " (SPDE's largest: " + trimmed(spde_high.max) +
                  "): its formula -V12 V22^-1 divides by V22, which is nearly singular in a few runs, and nothing "
                  "guards against that.");
  }

  // 2x2: from which level SPDE wins every entry, and what happens without noise in A.
  std::vector<std::vector<PairedComparison>> entry(paper.size());
  for (std::size_t l = 0; l < paper.size(); ++l) entry[l] = spde_vs_procrustes(paper[l]);
  std::size_t from = paper.size();
  for (std::size_t l = paper.size(); l-- > 0;) {
    bool wins = true;
    for (const PairedComparison& e : entry[l]) wins = wins && order_of(e) == Order::Lower;
    if (!wins) break;
    from = l;
  }
  if (from < paper.size()) {
    const EntryExperimentResult& last = paper.back();
    text = "2x2 example: from std_a = " + trimmed(kDemoLevels[from]) +
           " on, SPDE's mean absolute error is below Procrustes' for x11, x12 and x22; at std_a = " +
           trimmed(kDemoLevels.back()) + " it is";
    for (Eigen::Index e = 0; e < 3; ++e) {
      text += std::string(e ? "," : "") + " " + trimmed(last.of(Method::Spde).mae(e)) + " against " +
              trimmed(last.of(Method::SymmetricProcrustes).mae(e)) + " for " + kEntryNames[e];
    }
    text += ".";
  } else {
    text = "2x2 example: SPDE does not beat Procrustes on every entry at any of the levels run.";
  }
  std::string procrustes_better;
  for (std::size_t e = 0; e < 3; ++e) {
    if (order_of(entry.front()[e]) == Order::Higher) {
      procrustes_better += std::string(procrustes_better.empty() ? "" : ", ") + kEntryNames[e];
    }
  }
  text += " With no noise in A (std_a = 0) " +
          (procrustes_better.empty() ? std::string("the two are within noise of each other")
                                     : "Procrustes is the better one, for " + procrustes_better) +
          ": least squares assumes exactly that A is exact, and SPDE's area criterion, which allows for noise in A, "
          "has nothing to gain.";
  out << bullet(text);

  const experiment::EntryStatistics& tls_2x2 = paper.back().of(Method::TotalLeastSquares);
  const experiment::EntryStatistics& spde_2x2 = paper.back().of(Method::Spde);
  Eigen::Index worst = 0;
  (tls_2x2.std.array() / spde_2x2.std.array()).maxCoeff(&worst);
  if (tls_2x2.std(worst) > 5.0 * spde_2x2.std(worst)) {
    out << bullet("TLS allows for noise in A too, but is unstable: at std_a = " + trimmed(kDemoLevels.back()) +
                  " the standard deviation of its " + kEntryNames[worst] + " error is " + trimmed(tls_2x2.std(worst)) +
                  " against SPDE's " + trimmed(spde_2x2.std(worst)) +
                  " (the paper attributes this to TLS not enforcing positive definiteness).");
  }

  // More samples.
  const ThesisExperimentResult& most = samples.back();
  const Method best_large = best_of(most);
  const ThesisExperimentResult& middle = samples.front();
  auto fall = [&](Method method) {
    const double from_mean = middle.of(method).summary.mean, to_mean = most.of(method).summary.mean;
    const std::string name(to_string(method));
    return name + (name.back() == 's' ? "' by " : "'s by ") + percent(1.0 - to_mean / from_mean) + " (" +
           trimmed(from_mean) + " to " + trimmed(to_mean) + ")";
  };
  auto fall_fraction = [&](Method method) {
    return 1.0 - most.of(method).summary.mean / middle.of(method).summary.mean;
  };
  text = "More samples: from m = " + std::to_string(middle.options.simulation.samples) + " to " +
         std::to_string(most.options.simulation.samples) + " the mean error falls " + fall(Method::Spde) + ", " +
         fall(Method::TotalLeastSquaresSymmetric) + ", " + fall(Method::SymmetricProcrustes) + ".";
  if (best_large != Method::Spde) {
    const PairedComparison edge = compare_paired(most.of(best_large).errors, most.of(Method::Spde).errors);
    text += " At m = " + std::to_string(most.options.simulation.samples) + " " + std::string(to_string(best_large)) +
            " is the most accurate" +
            (order_of(edge) == Order::Lower ? " (" + fixed(-edge.mean_difference / edge.standard_error, 0) +
                                                  " standard errors below spde)"
                                            : std::string(", though not significantly below spde")) +
            ".";
    bool others_slower = true;
    for (Method method : kCompared) {
      others_slower = others_slower && (method == best_large || fall_fraction(method) < fall_fraction(best_large));
    }
    if (others_slower) text += " The others' errors fall more slowly with more data.";
    if (best_large == Method::TotalLeastSquaresSymmetric) {
      text += " TLS models noise of the same variance in A and B, which is what is simulated here; with real "
              "sensors, scale A and B to equal noise levels first (docs/hexapod.md).";
    }
  } else {
    text += " spde stays the most accurate at m = " + std::to_string(most.options.simulation.samples) + ".";
  }
  out << bullet(text);

  // The conclusion follows from the statements above.
  bool spde_best_small = true;
  for (const ThesisExperimentResult& r : thesis) spde_best_small = spde_best_small && best_of(r) == Method::Spde;
  std::string conclusion = "In short:";
  if (spde_best_small && all_lower && from < paper.size()) {
    conclusion += " with few samples (m = 12, as in the thesis) and noise in both the accelerations and the forces, "
                  "spde is the most accurate estimate;";
  } else {
    conclusion += " at m = 12 no method is the most accurate at every noise level (see the tables);";
  }
  conclusion += std::string(" when A is exact, symmetric Procrustes is ") +
                (procrustes_better.empty() ? "as good" : "as good or better");
  if (best_large != Method::Spde) {
    conclusion += "; with many samples (m = " + std::to_string(most.options.simulation.samples) + ") " +
                  std::string(to_string(best_large)) + " overtakes spde.";
  } else {
    conclusion += ", and spde keeps its lead with many samples.";
  }
  out << '\n' << wrap(conclusion);
  return out.str();
}

}  // namespace

Command add_demo_command(CLI::App& app, const GlobalOptions& global) {
  struct Cli {
    std::size_t trials = 2000, trials_2x2 = 10000, trials_samples = 300;
    std::uint64_t seed = 1;
    unsigned threads = 0;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = app.add_subcommand(
      "demo", "Run the thesis' and the paper's experiments on built-in data and explain what they show (a few seconds)");
  sub->add_option("--trials", cli->trials, "Monte Carlo trials per thesis experiment")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))
      ->capture_default_str();
  sub->add_option("--trials-2x2", cli->trials_2x2, "Monte Carlo trials per noise level of the 2x2 example")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))
      ->capture_default_str();
  sub->add_option("--trials-samples", cli->trials_samples,
                  "Monte Carlo trials at each of the larger sample sizes (m = 100, 1000)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))
      ->capture_default_str();
  sub->add_option("--seed", cli->seed, "Seed of every experiment")->capture_default_str();
  sub->add_option("--threads", cli->threads, "Worker threads (default: all cores)");

  auto run = [cli, &global]() {
    const auto start = std::chrono::steady_clock::now();
    experiment::MonteCarloOptions monte_carlo;
    monte_carlo.seed = cli->seed;
    monte_carlo.threads = cli->threads;

    std::vector<ThesisExperimentResult> thesis;
    monte_carlo.trials = cli->trials;
    for (const experiment::ThesisReportedRun& reported : experiment::kThesisReportedRuns) {
      experiment::ThesisExperimentOptions options;
      options.simulation.noise_var = reported.noise_var;
      monte_carlo.progress = terminal_progress("demo: thesis experiment " + std::to_string(reported.experiment), global.quiet);
      thesis.push_back(experiment::run_thesis_experiment(options, monte_carlo));
    }
    std::vector<ThesisExperimentResult> samples;
    monte_carlo.trials = cli->trials_samples;
    for (Eigen::Index m : kMoreSamples) {
      experiment::ThesisExperimentOptions options = thesis[1].options;
      options.simulation.samples = m;
      monte_carlo.progress = terminal_progress("demo: m = " + std::to_string(m) + " samples", global.quiet);
      samples.push_back(experiment::run_thesis_experiment(options, monte_carlo));
    }
    std::vector<EntryExperimentResult> paper;
    monte_carlo.trials = cli->trials_2x2;
    for (double std_a : kDemoLevels) {
      experiment::Paper2x2Options options;
      options.std_a = std_a;
      monte_carlo.progress = terminal_progress("demo: 2x2 example, std_a = " + trimmed(std_a), global.quiet);
      paper.push_back(experiment::run_paper_2x2(options, monte_carlo));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::ostringstream out;
    out << "spdfit demo: estimating a symmetric positive definite matrix from data with noise on both sides,\n"
        << "A X ~= B, on the experiments of the thesis (shared/seeds/000) and the paper (001).\n"
        << "Methods: ls (least squares), procrustes (symmetric least squares, thesis eq. 3.15), tls / tls-sym /\n"
        << "tls-psd (total least squares, eq. 4.37-4.39), spde (the area-criterion estimate, paper Theorem III.3).\n\n"
        << section_model() << section_thesis(thesis, cli->seed) << section_2x2(paper)
        << section_samples(thesis, samples) << section_findings(thesis, samples, paper);
    char line[200];
    std::snprintf(line, sizeof line,
                  "(seed %llu; %zu + %zu + %zu trials on %u threads in %.1f s. Reproduce any table with 'spdfit "
                  "experiment ...', see docs/hexapod.md.)",
                  static_cast<unsigned long long>(cli->seed), 3 * cli->trials, kMoreSamples.size() * cli->trials_samples,
                  kDemoLevels.size() * cli->trials_2x2,
                  experiment::resolve_threads(cli->threads), seconds);
    out << '\n' << wrap(line);
    emit(out.str(), "");
  };
  return {sub, run};
}

}  // namespace spdfit::cli
