// `spdfit demo`: its option table, the experiments it runs and its report (demo_tables.cpp,
// demo_findings.cpp).
#include "spdfit/experiment/demo.hpp"

#include <chrono>
#include <cstdio>
#include <limits>
#include <sstream>

#include "experiment/demo_report.hpp"
#include "interface/option_builders.hpp"
#include "spdfit/format.hpp"

namespace spdfit::experiment {

namespace {

using DemoSpec = OptionSpec<DemoRequest>;

// A count of trials: at least 1.
DemoSpec trials_entry(std::string_view name, std::string_view cli, std::string_view help, std::string_view default_text,
                      std::size_t DemoRequest::*member) {
  return spdfit::detail::integer_entry<DemoRequest>(name, cli, "", help, default_text, {1.0, 1e7}, member);
}

std::vector<DemoSpec> make_demo_table() {
  std::vector<DemoSpec> table;
  table.push_back(trials_entry("trials", "--trials", "Monte Carlo trials per thesis experiment", "2000",
                               &DemoRequest::trials));
  table.push_back(trials_entry("trials_2x2", "--trials-2x2", "Monte Carlo trials per noise level of the 2x2 example",
                               "10000", &DemoRequest::trials_2x2));
  table.push_back(trials_entry("trials_samples", "--trials-samples",
                               "Monte Carlo trials at each of the larger sample sizes (m = 100, 1000)", "300",
                               &DemoRequest::trials_samples));
  table.push_back(trials_entry("trials_beyond", "--trials-beyond",
                               "Monte Carlo trials at each point of section 5 (the methods beyond the seeds against m) "
                               "and in section 7 (units and noise)",
                               "200", &DemoRequest::trials_beyond));
  table.push_back(trials_entry("trials_physical", "--trials-physical",
                               "Monte Carlo trials at each m of section 6 (physical identification of the payload)",
                               "100", &DemoRequest::trials_physical));
  table.push_back(spdfit::detail::integer_entry<DemoRequest>(
      "seed", "--seed", "", "Seed of every experiment", "1", {0.0, double(std::numeric_limits<std::int64_t>::max())},
      &DemoRequest::seed));
  table.push_back(spdfit::detail::integer_entry<DemoRequest>("threads", "--threads", "", "Worker threads (0: one per core)",
                                                             "0", {0.0, 1024.0}, &DemoRequest::threads));
  return table;
}

}  // namespace

const std::vector<OptionSpec<DemoRequest>>& demo_option_table() {
  static const std::vector<DemoSpec> table = make_demo_table();
  return table;
}

DemoRun run_demo(const DemoRequest& request, const DemoProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const auto progress_for = [&progress](const std::string& label) {
    return progress ? progress(label) : std::function<void(std::size_t, std::size_t)>{};
  };
  MonteCarloOptions monte_carlo;
  monte_carlo.seed = request.seed;
  monte_carlo.threads = request.threads;

  auto results = std::make_shared<demo::Results>();
  results->seed = request.seed;
  std::vector<ThesisExperimentResult>& thesis = results->thesis;
  monte_carlo.trials = request.trials;
  for (const ThesisReportedRun& reported : kThesisReportedRuns) {
    ThesisExperimentOptions options;
    options.simulation.noise_var = reported.noise_var;
    monte_carlo.progress = progress_for("demo: thesis experiment " + std::to_string(reported.experiment));
    thesis.push_back(run_thesis_experiment(options, monte_carlo));
  }
  monte_carlo.trials = request.trials_samples;
  for (Eigen::Index m : demo::sample_sizes()) {
    ThesisExperimentOptions options = thesis[1].options;
    options.simulation.samples = m;
    monte_carlo.progress = progress_for("demo: m = " + std::to_string(m) + " samples");
    results->samples.push_back(run_thesis_experiment(options, monte_carlo));
  }
  monte_carlo.trials = request.trials_2x2;
  for (double std_a : demo::levels_2x2()) {
    Paper2x2Options options;
    options.std_a = std_a;
    monte_carlo.progress = progress_for("demo: 2x2 example, std_a = " + format_number(std_a));
    results->paper.push_back(run_paper_2x2(options, monte_carlo));
  }
  monte_carlo.trials = request.trials_beyond;
  for (double width : demo::beyond_widths()) {
    for (Eigen::Index m : demo::beyond_sizes()) {
      ThesisExperimentOptions options;
      options.simulation.noise_var = width * width / 12.0;  // uniform of width nm
      options.simulation.samples = m;
      options.methods = demo::beyond_methods();
      monte_carlo.progress = progress_for("demo: nm = " + format_number(width) + ", m = " + std::to_string(m));
      results->beyond.push_back(run_thesis_experiment(options, monte_carlo));
    }
  }
  monte_carlo.trials = request.trials_physical;
  {
    PhysicalExperimentOptions options;
    options.samples = demo::physical_sizes();
    monte_carlo.progress = progress_for("demo: physical identification");
    results->physical = run_physical_experiment(options, monte_carlo);
  }
  monte_carlo.trials = request.trials_beyond;
  monte_carlo.progress = progress_for("demo: units and noise");
  results->units = run_thesis_experiment(demo::units_options(), monte_carlo);

  DemoRun run;
  run.request = request;
  run.results = std::move(results);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.threads = resolve_threads(request.threads);
  return run;
}

std::string report(const DemoRun& run) {
  const DemoRequest& r = run.request;
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
      << demo::tables(*run.results) << demo::findings(*run.results);
  char line[200];
  std::snprintf(
      line, sizeof line,
      "(seed %llu; %zu + %zu + %zu + %zu + %zu + %zu trials on %u threads in %.1f s. Reproduce any table with "
      "'spdfit experiment ...', see docs/hexapod.md.)",
      static_cast<unsigned long long>(r.seed), 3 * r.trials, demo::sample_sizes().size() * r.trials_samples,
      demo::levels_2x2().size() * r.trials_2x2,
      demo::beyond_widths().size() * demo::beyond_sizes().size() * r.trials_beyond,
      demo::physical_sizes().size() * r.trials_physical, r.trials_beyond, run.threads, run.seconds);
  out << '\n' << demo::wrap(line);
  return out.str();
}

}  // namespace spdfit::experiment
