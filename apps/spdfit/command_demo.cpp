// spdfit demo: the source documents' experiments on built-in data, and what they show
// (the report itself is demo_tables.cpp and demo_findings.cpp).
#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "demo_report.hpp"
#include "experiment_output.hpp"
#include "output.hpp"
#include "spdfit/format.hpp"

namespace spdfit::cli {

using experiment::EntryExperimentResult;
using experiment::ThesisExperimentResult;

Command add_demo_command(CLI::App& app, const GlobalOptions& global) {
  struct Cli {
    std::size_t trials = 2000, trials_2x2 = 10000, trials_samples = 300, trials_beyond = 200,
                trials_physical = 100;
    std::uint64_t seed = 1;
    unsigned threads = 0;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = app.add_subcommand("demo",
                                     "Run the thesis' and the paper's experiments on built-in data and "
                                     "explain what they show (a few seconds)");
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
  sub->add_option("--trials-beyond", cli->trials_beyond,
                  "Monte Carlo trials at each point of section 5 (the methods beyond the seeds against m) and in "
                  "section 7 (units and noise)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))
      ->capture_default_str();
  sub->add_option("--trials-physical", cli->trials_physical,
                  "Monte Carlo trials at each m of section 6 (physical identification of the payload)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))
      ->capture_default_str();
  sub->add_option("--seed", cli->seed, "Seed of every experiment")->capture_default_str();
  sub->add_option("--threads", cli->threads, "Worker threads (default: all cores)");

  auto run = [cli, &global]() {
    const auto start = std::chrono::steady_clock::now();
    experiment::MonteCarloOptions monte_carlo;
    monte_carlo.seed = cli->seed;
    monte_carlo.threads = cli->threads;

    demo::Results results;
    results.seed = cli->seed;
    std::vector<ThesisExperimentResult>& thesis = results.thesis;
    monte_carlo.trials = cli->trials;
    for (const experiment::ThesisReportedRun& reported : experiment::kThesisReportedRuns) {
      experiment::ThesisExperimentOptions options;
      options.simulation.noise_var = reported.noise_var;
      monte_carlo.progress =
          trials_progress(global, "demo: thesis experiment " + std::to_string(reported.experiment));
      thesis.push_back(experiment::run_thesis_experiment(options, monte_carlo));
    }
    std::vector<ThesisExperimentResult>& samples = results.samples;
    monte_carlo.trials = cli->trials_samples;
    for (Eigen::Index m : demo::sample_sizes()) {
      experiment::ThesisExperimentOptions options = thesis[1].options;
      options.simulation.samples = m;
      monte_carlo.progress = trials_progress(global, "demo: m = " + std::to_string(m) + " samples");
      samples.push_back(experiment::run_thesis_experiment(options, monte_carlo));
    }
    std::vector<EntryExperimentResult>& paper = results.paper;
    monte_carlo.trials = cli->trials_2x2;
    for (double std_a : demo::levels_2x2()) {
      experiment::Paper2x2Options options;
      options.std_a = std_a;
      monte_carlo.progress =
          trials_progress(global, "demo: 2x2 example, std_a = " + format_number(std_a));
      paper.push_back(experiment::run_paper_2x2(options, monte_carlo));
    }
    monte_carlo.trials = cli->trials_beyond;
    for (double width : demo::beyond_widths()) {
      for (Eigen::Index m : demo::beyond_sizes()) {
        experiment::ThesisExperimentOptions options;
        options.simulation.noise_var = width * width / 12.0;  // uniform of width nm
        options.simulation.samples = m;
        options.methods = demo::beyond_methods();
        monte_carlo.progress = trials_progress(global, "demo: nm = " + format_number(width) + ", m = " + std::to_string(m));
        results.beyond.push_back(experiment::run_thesis_experiment(options, monte_carlo));
      }
    }
    monte_carlo.trials = cli->trials_physical;
    {
      experiment::PhysicalExperimentOptions options;
      options.samples = demo::physical_sizes();
      monte_carlo.progress = trials_progress(global, "demo: physical identification");
      results.physical = experiment::run_physical_experiment(options, monte_carlo);
    }
    monte_carlo.trials = cli->trials_beyond;
    monte_carlo.progress = trials_progress(global, "demo: units and noise");
    results.units = experiment::run_thesis_experiment(demo::units_options(), monte_carlo);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::ostringstream out;
    out << "spdfit demo: estimating a symmetric positive definite matrix from data with noise on both "
           "sides,\n"
        << "A X ~= B, on the experiments of the thesis (shared/seeds/000) and the paper (001).\n"
        << "Methods: ls (least squares), procrustes (symmetric least squares, thesis eq. 3.15), tls / "
           "tls-sym /\n"
        << "tls-psd (total least squares, eq. 4.37-4.39), spde (the area-criterion estimate, paper Theorem "
           "III.3);\n"
        << "beyond the seeds: spd-tls (total least squares over the SPD matrices), psd-ls (least squares over "
           "X >= 0)\n"
        << "and auto (spde, spd-tls or psd-ls, chosen from the data).\n\n"
        << demo::tables(results) << demo::findings(results);
    char line[200];
    std::snprintf(
        line, sizeof line,
        "(seed %llu; %zu + %zu + %zu + %zu + %zu + %zu trials on %u threads in %.1f s. Reproduce any table with "
        "'spdfit experiment ...', see docs/hexapod.md.)",
        static_cast<unsigned long long>(cli->seed), 3 * cli->trials,
        demo::sample_sizes().size() * cli->trials_samples, demo::levels_2x2().size() * cli->trials_2x2,
        demo::beyond_widths().size() * demo::beyond_sizes().size() * cli->trials_beyond,
        demo::physical_sizes().size() * cli->trials_physical, cli->trials_beyond,
        experiment::resolve_threads(cli->threads), seconds);
    out << '\n' << demo::wrap(line);
    emit(out.str(), "");
  };
  return {sub, run};
}

}  // namespace spdfit::cli
