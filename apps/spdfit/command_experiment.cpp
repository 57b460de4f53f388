// spdfit experiment thesis|paper-hexapod|paper-2x2: the seeds' Monte Carlo experiments.
#include <algorithm>
#include <cmath>
#include <CLI/CLI.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "experiment_output.hpp"
#include "output.hpp"
#include "payload_options.hpp"
#include "simulation_noise_options.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "validators.hpp"

namespace spdfit::cli {

namespace {

// Options every experiment has.
struct CommonCli {
  std::size_t trials = 0;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool json = false;
  std::string csv, output;
};

void add_common(CLI::App* sub, CommonCli& common, std::size_t default_trials) {
  common.trials = default_trials;
  sub->add_option("--trials", common.trials, "Number of Monte Carlo trials")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))
      ->capture_default_str();
  sub->add_option("--seed", common.seed,
                  "Seed: the same seed gives the same numbers on any number of threads")
      ->capture_default_str();
  sub->add_option("--threads", common.threads, "Worker threads (default: all cores)");
  sub->add_flag("--json", common.json, "Print the results as JSON");
  sub->add_option("--csv", common.csv, "Also write a CSV table to FILE (see the command's help)");
  sub->add_option("-o,--output", common.output, "Write to FILE instead of stdout");
}

// --methods a,b,...: which estimators an experiment runs (default: the experiment's own set).
void add_methods(CLI::App* sub, std::vector<std::string>& names, const std::vector<Method>& defaults) {
  std::vector<std::string> known, shown;
  for (Method m : kSelectableMethods) known.emplace_back(to_string(m));
  for (Method m : defaults) shown.emplace_back(to_string(m));
  std::string default_text;
  for (const std::string& name : shown) default_text += (default_text.empty() ? "" : ",") + name;
  sub->add_option("--methods", names, "Comma-separated methods to run (default: " + default_text + ")")
      ->delimiter(',')
      ->check(CLI::IsMember(known));
}

// The methods named on the command line, or `defaults`; a usage error for a repeat.
std::vector<Method> chosen_methods(const std::vector<std::string>& names, const std::vector<Method>& defaults) {
  if (names.empty()) return defaults;
  std::vector<Method> methods;
  for (const std::string& name : names) {
    const Method method = *parse_method(name);
    for (Method earlier : methods) {
      if (earlier == method) throw UsageError("--methods: " + name + " is listed twice");
    }
    methods.push_back(method);
  }
  return methods;
}

// Whether the results include both methods (the text reports compare them when they do).
template <typename Result>
bool has_both(const Result& result, Method a, Method b) {
  bool found_a = false, found_b = false;
  for (const auto& m : result.methods) {
    found_a = found_a || m.method == a;
    found_b = found_b || m.method == b;
  }
  return found_a && found_b;
}

experiment::MonteCarloOptions monte_carlo(const CommonCli& common, const std::string& label,
                                          const GlobalOptions& global) {
  experiment::MonteCarloOptions options;
  options.trials = common.trials;
  options.seed = common.seed;
  options.threads = common.threads;
  options.progress = trials_progress(global, label);
  return options;
}

// Options of the hexapod generator.
struct SimulationCli {
  hexapod::SimulationOptions options;
  std::string distribution = "uniform";
  double force_noise_var = 0.0;
  CLI::Option* force_noise = nullptr;
  CLI::Option* noise_var = nullptr;
  bool noise_required = false;
  SimulationNoiseCli noise;
};

void add_simulation(CLI::App* sub, SimulationCli& simulation, bool noise_required) {
  auto* noise =
      sub->add_option("--noise-var", simulation.options.noise_var,
                      "Variance V of the noise in every entry of A and B (thesis: 0.082, 0.86, 1.28)")
          ->check(non_negative());
  simulation.noise_var = noise;
  simulation.noise_required = noise_required;
  if (!noise_required) noise->capture_default_str();
  simulation.force_noise =
      sub->add_option(
             "--force-noise-var", simulation.force_noise_var,
             "Variance of the noise in B when it differs from A's (default: --noise-var, as the thesis)")
          ->check(non_negative());
  sub->add_option("--samples", simulation.options.samples, "Samples m (rows of A and B)")
      ->check(integer_in(6, 100000000))
      ->capture_default_str();
  sub->add_option("--signal-var", simulation.options.signal_var,
                  "Variance of the true accelerations, uniform on [-sqrt(3 S), sqrt(3 S)] (thesis: 25/3)")
      ->check(positive());
  sub->add_option("--distribution", simulation.distribution,
                  "Noise distribution: uniform (the thesis') or gaussian")
      ->check(CLI::IsMember({"uniform", "gaussian"}))
      ->capture_default_str();
  add_simulation_noise_options(*sub, simulation.noise, noise);
}

hexapod::SimulationOptions simulation_options(const SimulationCli& simulation) {
  if (simulation.noise_required && simulation.noise_var->count() == 0 && !gives_noise_std(simulation.noise)) {
    throw UsageError("give the noise: --noise-var V, or --noise-std-a S and --noise-std-b S");
  }
  hexapod::SimulationOptions options = simulation.options;
  if (gives_noise_std(simulation.noise)) options.noise_var = 0.0;  // the per-sensor deviations instead
  options.distribution = *hexapod::parse_noise_distribution(simulation.distribution);
  if (simulation.force_noise->count() > 0) options.force_noise_var = simulation.force_noise_var;
  apply_simulation_noise_options(simulation.noise, options);
  return options;
}

std::string describe(const hexapod::SimulationOptions& s) {
  std::ostringstream out;
  out << "m = " << s.samples << " samples of 6 strut accelerations (uniform, variance "
      << format_fixed(s.signal_var, 3) << "),\n"
      << hexapod::to_string(s.distribution) << " noise of variance " << s.noise_var;
  if (s.noise_std_a || s.noise_std_b) {
    const auto list = [](const std::optional<Eigen::VectorXd>& v, double variance) {
      if (!v) return format_number(std::sqrt(variance), Precision::Medium);
      std::string text;
      for (Eigen::Index i = 0; i < v->size(); ++i) text += (i ? ", " : "") + format_number((*v)(i), Precision::Medium);
      return text;
    };
    out.str("");
    out << "m = " << s.samples << " samples of 6 strut accelerations (uniform, variance "
        << format_fixed(s.signal_var, 3) << "),\n"
        << hexapod::to_string(s.distribution) << " noise of standard deviation " << list(s.noise_std_a, s.noise_var)
        << " in A and " << list(s.noise_std_b, s.force_noise_var.value_or(s.noise_var)) << " in B";
  } else if (s.force_noise_var && *s.force_noise_var != s.noise_var) {
    out << " in every entry of A and " << *s.force_noise_var << " in every entry of B";
  } else {
    out << " in every entry of A and B";
  }
  if (s.scale_b != 1.0) out << ", B scaled by " << format_number(s.scale_b, Precision::Medium);
  if (s.rest_samples > 0) out << ", " << s.rest_samples << " rows at rest";
  return out.str();
}

Command add_thesis(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    CommonCli common;
    SimulationCli simulation;
    std::vector<std::string> methods;
    std::vector<std::string> fit_noise;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "thesis",
      "The thesis' chapter-6 experiment (M_p of eq. 6.1, appendix-B generator), repeated --trials times");
  add_simulation(sub, cli->simulation, true);
  add_common(sub, cli->common, 1000);
  add_methods(sub, cli->methods, experiment::ThesisExperimentOptions{}.methods);
  sub->add_option("--fit-noise", cli->fit_noise,
                  "Comma-separated noise models to fit every method with, each in turn: none (equal noise "
                  "assumed), true (the generator's covariances), rest (the covariances of the trial's "
                  "--rest-samples rows); spde runs with none only (default: none)")
      ->delimiter(',')
      ->check(CLI::IsMember({"none", "true", "rest"}));
  sub->footer("--csv FILE writes each trial's error ||M_p - M_hat||_F per method (one row per trial).");

  auto run = [cli, &global]() {
    experiment::ThesisExperimentOptions options;
    options.simulation = simulation_options(cli->simulation);
    options.methods = chosen_methods(cli->methods, options.methods);
    if (!cli->fit_noise.empty()) {
      options.noise_models.clear();
      for (const std::string& name : cli->fit_noise) {
        const experiment::FitNoise noise = *experiment::parse_fit_noise(name);
        for (experiment::FitNoise earlier : options.noise_models) {
          if (earlier == noise) throw UsageError("--fit-noise: " + name + " is listed twice");
        }
        options.noise_models.push_back(noise);
      }
      const bool rest = std::find(options.noise_models.begin(), options.noise_models.end(),
                                  experiment::FitNoise::Rest) != options.noise_models.end();
      if (rest && options.simulation.rest_samples < 2) {
        throw UsageError("--fit-noise rest needs --rest-samples N (N >= 2): the rows recorded at rest");
      }
    }
    const experiment::ThesisExperimentResult result =
        experiment::run_thesis_experiment(options, monte_carlo(cli->common, "experiment thesis", global));
    if (!cli->common.csv.empty()) emit(thesis_csv(result), cli->common.csv);
    if (cli->common.json) {
      emit(thesis_json(result).dump(2) + "\n", cli->common.output);
      return;
    }
    std::ostringstream out;
    out << "Thesis experiment (seed 000, chapter 6), M_p of eq. 6.1:\n"
        << describe(result.options.simulation) << ".\n"
        << result.trials << " trials, seed " << result.seed << ". Error ||M_p - M_hat||_F:\n\n"
        << thesis_table(result);
    if (has_both(result, Method::Spde, Method::SymmetricProcrustes)) {
      out << '\n' << paired_line(result, Method::Spde, Method::SymmetricProcrustes);
    }
    emit(out.str(), cli->common.output);
  };
  return {sub, run};
}

Command add_paper_hexapod(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    CommonCli common;
    SimulationCli simulation;
    std::vector<std::string> methods;
  };
  auto cli = std::make_shared<Cli>();
  cli->simulation.options = experiment::PaperHexapodOptions::default_simulation();
  CLI::App* sub = parent.add_subcommand("paper-hexapod",
                                        "The paper's Figure 2: per-entry error statistics of the 21 "
                                        "parameters of M_p, Procrustes against SPDE");
  add_simulation(sub, cli->simulation, false);
  add_common(sub, cli->common, 100);
  add_methods(sub, cli->methods, experiment::PaperHexapodOptions{}.methods);
  sub->footer(
      "The paper's data came from sensors whose noise it does not give; the default is the thesis'\n"
      "Experiment 2 level (V = 0.86, m = 12, uniform). --csv FILE writes method,entry,true,mae,std,bias.");

  auto run = [cli, &global]() {
    experiment::PaperHexapodOptions options;
    options.simulation = simulation_options(cli->simulation);
    options.methods = chosen_methods(cli->methods, options.methods);
    const experiment::EntryExperimentResult result =
        experiment::run_paper_hexapod(options, monte_carlo(cli->common, "experiment paper-hexapod", global));
    if (!cli->common.csv.empty()) emit(entry_csv(result, "m"), cli->common.csv);
    if (cli->common.json) {
      nlohmann::json out;
      out["experiment"] = "paper-hexapod";
      out["noise_var"] = options.simulation.noise_var;
      out["force_noise_var"] = options.simulation.force_noise_var.value_or(options.simulation.noise_var);
      out["samples"] = options.simulation.samples;
      out["trials"] = result.trials;
      out["seed"] = result.seed;
      out["signal_var"] = options.simulation.signal_var;
      out["distribution"] = std::string(hexapod::to_string(options.simulation.distribution));
      out["entries"] = entries_json(result);
      out["truth"] = matrix_json(result.truth);
      out["methods"] = entry_methods_json(result);
      emit(out.dump(2) + "\n", cli->common.output);
      return;
    }
    std::ostringstream out;
    out << "The paper's hexapod experiment (seed 001, Figure 2), M_p of thesis eq. 6.1:\n"
        << describe(options.simulation) << ".\n"
        << result.trials << " trials, seed " << result.seed
        << ". |e|: mean absolute error; std e: standard deviation of the error.\n\n"
        << entry_table(result, "m");
    if (has_both(result, Method::Spde, Method::SymmetricProcrustes)) {
      const experiment::EntryExperimentResult::Wins wins = result.wins(Method::Spde, Method::SymmetricProcrustes);
      out << '\n'
          << "spde has the smaller mean absolute error on " << wins.mae << " of " << wins.entries
          << " entries and the smaller standard deviation on " << wins.std << ".\n";
    }
    emit(out.str(), cli->common.output);
  };
  return {sub, run};
}

Command add_paper_2x2(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    CommonCli common;
    experiment::Paper2x2Options options;
    bool sweep = false;
    std::vector<std::string> methods;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "paper-2x2",
      "The paper's 2x2 example (Figure 3): X = [3 1; 1 1] from A X ~= B with Gaussian noise in A and B");
  auto* std_a = sub->add_option("--std-a", cli->options.std_a, "Standard deviation of the noise in A")
                    ->check(non_negative());
  sub->add_option("--std-b", cli->options.std_b, "Standard deviation of the noise in B")
      ->check(non_negative())
      ->capture_default_str();
  auto* sweep =
      sub->add_flag("--sweep", cli->sweep,
                    "Run std_a = 0, 0.1, ..., 1.9 (Figure 3) and print the table as CSV (with --csv "
                    "FILE: write it there and print a readable table)");
  sweep->excludes(std_a);
  add_common(sub, cli->common, 10000);
  add_methods(sub, cli->methods, experiment::Paper2x2Options{}.methods);
  sub->footer(
      "Methods (default): procrustes (least squares), tls (unsymmetrized, the paper's footnote 2), spde.\n"
      "mae: mean |x_hat - x|; std: standard deviation of x_hat - x; bias: mean of x_hat - x.");

  auto run = [cli, std_a, &global]() {
    if (!cli->sweep && std_a->count() == 0)
      throw UsageError("experiment paper-2x2: give --std-a VA, or --sweep");
    cli->options.methods = chosen_methods(cli->methods, experiment::Paper2x2Options{}.methods);
    if (cli->sweep) {
      const std::vector<double> levels = experiment::paper_2x2_sweep_levels();
      const std::vector<experiment::EntryExperimentResult> results = experiment::run_paper_2x2_sweep(
          cli->options, levels, monte_carlo(cli->common, "experiment paper-2x2 --sweep", global));
      const std::string csv = sweep_csv(levels, cli->options.std_b, results);
      if (!cli->common.csv.empty()) emit(csv, cli->common.csv);
      if (cli->common.json) {
        nlohmann::json out;
        out["experiment"] = "paper-2x2";
        out["sweep"] = true;
        out["std_b"] = cli->options.std_b;
        out["trials"] = cli->common.trials;
        out["seed"] = cli->common.seed;
        out["entries"] = entries_json(results.front());
        out["levels"] = nlohmann::json::array();
        for (std::size_t l = 0; l < levels.size(); ++l) {
          out["levels"].push_back({{"std_a", levels[l]}, {"methods", entry_methods_json(results[l])}});
        }
        emit(out.dump(2) + "\n", cli->common.output);
      } else if (!cli->common.csv.empty()) {
        std::ostringstream out;
        out << "The paper's 2x2 example (seed 001, Figure 3), std_b = " << cli->options.std_b << ", "
            << cli->common.trials << " trials per level, seed " << cli->common.seed << "; table written to "
            << cli->common.csv << ".\n\n"
            << sweep_table(levels, results);
        emit(out.str(), cli->common.output);
      } else {
        emit(csv, cli->common.output);
      }
      return;
    }
    const experiment::EntryExperimentResult result =
        experiment::run_paper_2x2(cli->options, monte_carlo(cli->common, "experiment paper-2x2", global));
    if (!cli->common.csv.empty()) emit(entry_csv(result, "x"), cli->common.csv);
    if (cli->common.json) {
      nlohmann::json out;
      out["experiment"] = "paper-2x2";
      out["std_a"] = cli->options.std_a;
      out["std_b"] = cli->options.std_b;
      out["trials"] = result.trials;
      out["seed"] = result.seed;
      out["entries"] = entries_json(result);
      out["truth"] = matrix_json(result.truth);
      out["methods"] = entry_methods_json(result);
      emit(out.dump(2) + "\n", cli->common.output);
      return;
    }
    std::ostringstream out;
    out << "The paper's 2x2 example (seed 001, Figure 3): std_a = " << cli->options.std_a
        << ", std_b = " << cli->options.std_b << "; " << result.trials << " trials, seed " << result.seed
        << ".\n|e|: mean absolute error; std e: standard deviation of the error.\n\n"
        << entry_table(result, "x");
    emit(out.str(), cli->common.output);
  };
  return {sub, run};
}

Command add_physical(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    CommonCli common;
    experiment::PhysicalExperimentOptions options;
    std::vector<Eigen::Index> samples;
    std::vector<std::string> methods;
    std::string distribution = "uniform", geometry;
    double force_noise_var = 0.0;
    CLI::Option* force_noise = nullptr;
    PayloadCli payload;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "physical",
      "Physical identification of the payload against the generic estimators: error of M_p over m, and how "
      "often each estimate is physically consistent");
  const experiment::PhysicalExperimentOptions defaults;
  sub->add_option("--samples", cli->samples, "Comma-separated numbers of samples m (default 12,30,100,1000)")
      ->delimiter(',')
      ->check(CLI::Range(Eigen::Index{6}, Eigen::Index{100000000}));
  sub->add_option("--noise-var", cli->options.simulation.noise_var,
                  "Variance of the noise in every entry of A and B (default 3.2^2/12: uniform of width 3.2)")
      ->check(non_negative());
  cli->force_noise = sub->add_option("--force-noise-var", cli->force_noise_var,
                                     "Variance of the noise in B when it differs from A's")
                         ->check(non_negative());
  sub->add_option("--distribution", cli->distribution, "Noise distribution: uniform or gaussian")
      ->check(CLI::IsMember({"uniform", "gaussian"}))
      ->capture_default_str();
  sub->add_option("--geometry", cli->geometry, "Hexapod geometry file (default: the built-in cubic hexapod)");
  add_payload_options(sub, cli->payload);
  add_common(sub, cli->common, 200);
  std::string variants, generic;
  for (const std::string& v : experiment::physical_variant_names())
    variants += (variants.empty() ? "" : ", ") + v;
  for (Method m : kSelectableMethods) generic += (generic.empty() ? "" : ", ") + std::string(to_string(m));
  sub->add_option("--methods", cli->methods,
                  "Comma-separated estimators: generic methods (" + generic + ") and physical variants (" +
                      variants +
                      ", with :common or :each to estimate the strut masses) (default: spde,spd-tls,physical,"
                      "grey-box-ls,grey-box-tls)")
      ->delimiter(',');
  sub->footer(
      "physical: spdfit's estimator (errors in variables, physically consistent); physical-ls: its convex "
      "least-\n"
      "squares start; grey-box-tls and grey-box-ls: the same model without the consistency constraint.");

  auto run = [cli, &global]() {
    if (!cli->common.csv.empty()) throw UsageError("experiment physical writes no CSV: use --json");
    experiment::PhysicalExperimentOptions options = cli->options;
    if (!cli->samples.empty()) options.samples = cli->samples;
    options.simulation.distribution = *hexapod::parse_noise_distribution(cli->distribution);
    if (cli->force_noise->count() > 0) options.simulation.force_noise_var = cli->force_noise_var;
    if (!cli->geometry.empty()) options.geometry = hexapod::read_geometry(cli->geometry);
    if (cli->payload.given()) {
      options.payload =
          payload_of(cli->payload, options.geometry ? *options.geometry : hexapod::cubic_geometry());
    }
    if (!cli->methods.empty()) {
      try {
        experiment::set_estimators(options, cli->methods);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--methods: ") + e.what());
      }
    }
    std::string error;
    if (!options.is_valid(&error))
      throw UsageError("experiment physical: " + spell_options(error, Frontend::Cli));
    const experiment::PhysicalExperimentResult result =
        experiment::run_physical_experiment(options, monte_carlo(cli->common, "experiment physical", global));
    emit(cli->common.json ? experiment::to_json(result) : experiment::report(result), cli->common.output);
  };
  return {sub, run};
}

}  // namespace

Command add_experiment_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub = app.add_subcommand("experiment", "Monte Carlo experiments of the source documents");
  sub->require_subcommand(1);
  auto children = std::make_shared<std::vector<Command>>(
      std::vector<Command>{add_thesis(*sub, global), add_paper_hexapod(*sub, global),
                           add_paper_2x2(*sub, global), add_physical(*sub, global)});
  auto run = [children]() {
    for (const Command& child : *children) {
      if (child.app->parsed()) child.run();
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
