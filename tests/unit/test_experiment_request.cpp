// The experiments' requests (experiment_request.hpp, demo.hpp) and linkage analyze's
// (linkage/analyze_request.hpp): a request from the option tables runs the same experiment as its
// options built by hand, and its refusals carry a usage code naming the option.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "spdfit/experiment/demo.hpp"
#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/linkage/analyze_request.hpp"
#include "spdfit/linkage/prescribed_function.hpp"

namespace spdfit {
namespace {

using namespace spdfit::experiment;

// Sets each (library name, value) of `values` through `kind`'s table, as a front end does.
ExperimentRequest request_of(ExperimentKind kind, const std::vector<std::pair<std::string, OptionValue>>& values,
                             std::vector<std::string_view>& given) {
  ExperimentRequest request = experiment_request(kind);
  for (const auto& [name, value] : values) {
    const OptionSpec<ExperimentRequest>* spec = find_option(experiment_option_table(kind), name);
    EXPECT_NE(spec, nullptr) << name;
    set_option(request, *spec, value);
    given.push_back(spec->name);
  }
  return request;
}

Code code_of_refusal(ExperimentKind kind, const std::vector<std::pair<std::string, OptionValue>>& values) {
  std::vector<std::string_view> given;
  try {
    const ExperimentRequest request = request_of(kind, values, given);
    run_experiment(request, given);
  } catch (const OptionError& e) {
    return e.code();
  }
  return Code::Internal;
}

TEST(ExperimentRequest, ThesisFromTheTableIsTheThesisExperiment) {
  std::vector<std::string_view> given;
  const ExperimentRequest request = request_of(
      ExperimentKind::Thesis,
      {{"noise_var", 0.86}, {"trials", std::int64_t{40}}, {"seed", std::int64_t{3}}, {"methods", std::string("spde, procrustes")}},
      given);
  const ExperimentRun run = run_experiment(request, given);
  ThesisExperimentOptions options;
  options.simulation.noise_var = 0.86;
  options.methods = {Method::Spde, Method::SymmetricProcrustes};
  MonteCarloOptions monte_carlo;
  monte_carlo.trials = 40;
  monte_carlo.seed = 3;
  const ThesisExperimentResult direct = run_thesis_experiment(options, monte_carlo);
  ASSERT_TRUE(run.thesis.has_value());
  ASSERT_EQ(run.thesis->methods.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(run.thesis->methods[k].method, direct.methods[k].method);
    EXPECT_EQ(run.thesis->methods[k].errors, direct.methods[k].errors);
  }
  // The CSV has a row per trial and a column per method.
  const std::string csv = to_csv(run);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 41);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "trial,spde,procrustes");
}

TEST(ExperimentRequest, DefaultsAreEachExperimentsOwn) {
  EXPECT_EQ(experiment_request(ExperimentKind::Thesis).trials, 1000u);
  EXPECT_EQ(experiment_request(ExperimentKind::PaperHexapod).trials, 100u);
  EXPECT_EQ(experiment_request(ExperimentKind::Paper2x2).trials, 10000u);
  EXPECT_EQ(experiment_request(ExperimentKind::Physical).trials, 200u);
  EXPECT_EQ(experiment_request(ExperimentKind::PaperHexapod).simulation.options.noise_var,
            PaperHexapodOptions::default_simulation().noise_var);
  EXPECT_EQ(experiment_request(ExperimentKind::Physical).simulation.options.noise_var,
            PhysicalExperimentOptions{}.simulation.noise_var);
}

TEST(ExperimentRequest, RefusalsAreUsageErrors) {
  // The thesis needs its noise; methods and noise models once each; rest needs rest rows.
  EXPECT_EQ(code_of_refusal(ExperimentKind::Thesis, {}), Code::OptionConflict);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Thesis, {{"noise_var", 1.0}, {"methods", std::string("spde,spde")}}),
            Code::OptionValue);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Thesis, {{"noise_var", 1.0}, {"methods", std::string("bogus")}}),
            Code::OptionValue);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Thesis, {{"noise_var", 1.0}, {"fit_noise", std::string("rest")}}),
            Code::OptionConflict);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Paper2x2, {}), Code::OptionConflict);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Paper2x2, {{"std_a", 1.0}, {"sweep", true}}), Code::OptionConflict);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Physical, {{"payload_mass", -3.0}}), Code::OptionValue);
  EXPECT_EQ(code_of_refusal(ExperimentKind::Physical, {{"methods", std::string("spde,spde")}}), Code::OptionValue);
}

TEST(ExperimentRequest, SweepRunsEveryLevel) {
  std::vector<std::string_view> given;
  const ExperimentRequest request =
      request_of(ExperimentKind::Paper2x2, {{"sweep", true}, {"trials", std::int64_t{20}}}, given);
  const ExperimentRun run = run_experiment(request, given);
  EXPECT_EQ(run.levels, paper_2x2_sweep_levels());
  ASSERT_EQ(run.entries.size(), run.levels.size());
  // Without a CSV file the report is the CSV table; with one, a table that names it.
  EXPECT_EQ(report(run), to_csv(run));
  EXPECT_NE(report(run, "sweep.csv").find("table written to sweep.csv"), std::string::npos);
}

TEST(DemoRequest, TableSetsEveryCount) {
  DemoRequest request;
  for (const OptionSpec<DemoRequest>& spec : demo_option_table()) set_option(request, spec, std::int64_t{7});
  EXPECT_EQ(request.trials, 7u);
  EXPECT_EQ(request.trials_2x2, 7u);
  EXPECT_EQ(request.trials_samples, 7u);
  EXPECT_EQ(request.trials_beyond, 7u);
  EXPECT_EQ(request.trials_physical, 7u);
  EXPECT_EQ(request.seed, 7u);
  EXPECT_EQ(request.threads, 7u);
}

TEST(AnalyzeRequest, IsTheAnalysisAtEvenlySpacedAngles) {
  linkage::AnalyzeRequest request;
  request.lengths = {4.0, 1.0, 3.5, 3.0};
  request.psi_range = "-90:90";
  request.points = 7;
  const linkage::Analysis run = linkage::run_analyze(request);
  const double degree = std::acos(-1.0) / 180.0;
  const linkage::Analysis direct = linkage::analyze(
      linkage::FourBar{4.0, 1.0, 3.5, 3.0},
      linkage::spaced_points(-90.0 * degree, 90.0 * degree, 7, linkage::Spacing::Uniform));
  ASSERT_EQ(run.samples.size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_EQ(run.samples[k].psi, direct.samples[k].psi);
    EXPECT_EQ(run.samples[k].phi_plus, direct.samples[k].phi_plus);
  }
  const auto refused = [](linkage::AnalyzeRequest r) {
    try {
      linkage::run_analyze(r);
    } catch (const OptionError& e) {
      return e.subject();
    }
    return std::string("accepted");
  };
  linkage::AnalyzeRequest three = request;
  three.lengths = {1.0, 2.0, 3.0};
  EXPECT_EQ(refused(three), "lengths");
  linkage::AnalyzeRequest reversed = request;
  reversed.psi_range = "90:10";
  EXPECT_EQ(refused(reversed), "psi_range");
}

}  // namespace
}  // namespace spdfit
