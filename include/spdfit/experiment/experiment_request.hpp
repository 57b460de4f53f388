// `spdfit experiment thesis|paper-hexapod|paper-2x2|physical`: the request (the Monte Carlo
// settings, the generator's, the methods), one option table per experiment, and the experiments'
// own options built from it, so that the command line's options come from the library.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"

namespace spdfit::experiment {

/// The experiments of `spdfit experiment`.
enum class ExperimentKind { Thesis, PaperHexapod, Paper2x2, Physical };

/// Every experiment, in the order `spdfit experiment --help` lists them.
inline constexpr std::array<ExperimentKind, 4> kExperimentKinds = {
    ExperimentKind::Thesis, ExperimentKind::PaperHexapod, ExperimentKind::Paper2x2, ExperimentKind::Physical};

/// The command line's name of an experiment ("paper-2x2").
std::string_view to_string(ExperimentKind kind);

/// What an experiment runs and how the command line reports it.
struct ExperimentRequest {
  ExperimentKind kind = ExperimentKind::Thesis;
  std::size_t trials = 1000;  ///< the experiment's own default (experiment_request)
  std::uint64_t seed = 1;
  unsigned threads = 0;  ///< 0: one per core; the numbers do not depend on it
  /// Comma-separated names of the methods to run (physical: generic methods and physical
  /// variants); empty: the experiment's own set.
  std::string methods;
  /// The generator (thesis, paper-hexapod; physical: its noise, geometry and payload).
  hexapod::SimulateRequest simulation;
  std::string fit_noise;               ///< thesis: comma-separated none, true, rest; empty: none
  std::optional<double> std_a;         ///< paper-2x2: the noise in A (or `sweep`)
  double std_b = Paper2x2Options{}.std_b;
  bool sweep = false;                  ///< paper-2x2: every level of Figure 3
  std::vector<double> levels;          ///< the sweep's std_a; empty: Figure 3's (paper_2x2_sweep_levels)
  std::vector<Eigen::Index> samples;   ///< physical: the numbers of samples; empty: its own
  std::string csv;                     ///< also write a CSV table to this file (not physical)
  OutputRequest output;                ///< `json` and `output`
};

/// A request for `kind` with its defaults: its trials (thesis 1000, paper-hexapod 100, paper-2x2
/// 10000, physical 200) and its generator's settings.
ExperimentRequest experiment_request(ExperimentKind kind);

/// The options of `spdfit experiment KIND`.
const std::vector<OptionSpec<ExperimentRequest>>& experiment_option_table(ExperimentKind kind);

/// The table's rules (check_option_combination of the names `given`) and the experiment's:
/// the thesis needs its noise, paper-2x2 `std_a` or `sweep`, methods and noise models listed
/// once each and known. OptionError naming the option.
void check_experiment_request(const ExperimentRequest& request, const std::vector<std::string_view>& given);

/// The Monte Carlo settings (no progress callback: the front end adds its own).
MonteCarloOptions monte_carlo_options(const ExperimentRequest& request);

/// Each experiment's options from a checked request. OptionError for a value the experiment
/// refuses (a generator's setting, a payload that is not a body); physical_options reads the
/// geometry's file (io::DataError).
ThesisExperimentOptions thesis_options(const ExperimentRequest& request);
PaperHexapodOptions paper_hexapod_options(const ExperimentRequest& request);
Paper2x2Options paper_2x2_options(const ExperimentRequest& request);
PhysicalExperimentOptions physical_options(const ExperimentRequest& request);

/// An experiment's results with the options it ran with, for its renderings.
struct ExperimentRun {
  ExperimentKind kind = ExperimentKind::Thesis;
  std::size_t trials = 0;
  std::uint64_t seed = 1;
  std::optional<ThesisExperimentResult> thesis;
  PaperHexapodOptions paper_hexapod;
  Paper2x2Options paper_2x2;
  bool sweep = false;
  std::vector<double> levels;                  ///< the sweep's std_a
  std::vector<EntryExperimentResult> entries;  ///< paper-hexapod, paper-2x2: one; the sweep: one per level
  std::optional<PhysicalExperimentResult> physical;
};

/// The workflow of `spdfit experiment KIND`: the request checked (check_experiment_request with
/// the options `given`), the experiment's options built, its trials run (`progress` as
/// MonteCarloOptions::progress). OptionError for the request; what the experiment throws.
ExperimentRun run_experiment(const ExperimentRequest& request, const std::vector<std::string_view>& given,
                             const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The run as the command line's JSON document.
std::string to_json(const ExperimentRun& run);

/// The run for people. The 2x2 sweep prints its CSV table (to_csv) unless `csv_path` says where
/// the table was written; then a readable table that names the file.
std::string report(const ExperimentRun& run, const std::string& csv_path = {});

/// The run's CSV table (the thesis: one row per trial; the entries: method,entry,true,mae,std,bias;
/// the sweep: one row per level and method); empty for the physical experiment, which has none.
std::string to_csv(const ExperimentRun& run);

}  // namespace spdfit::experiment
