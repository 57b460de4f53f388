// Internal: the Monte Carlo experiments' tables for people, JSON and CSV, for `spdfit experiment`'s
// renderings (experiment_request.hpp: to_json, report, to_csv of an ExperimentRun) and the demo's.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/hexapod/simulate.hpp"

namespace spdfit::experiment::detail {

/// {"mean", "std", "median", "max", "min", "standard_error", "count", "failures"}.
nlohmann::json summary_json(const Summary& summary);

/// A method's label in the thesis experiment's outputs: its name, and the noise model it was
/// fitted with when that is not none ("spd-tls/rest").
std::string method_label(const MethodErrors& m);

/// The thesis experiment: {"experiment", "noise_var", ..., "methods": {label: summary}}; its table
/// of errors per method; the paired comparison of two methods (one line); one row per trial.
nlohmann::json thesis_json(const ThesisExperimentResult& result);
std::string thesis_table(const ThesisExperimentResult& result);
std::string paired_line(const ThesisExperimentResult& result, Method a, Method b);
std::string thesis_csv(const ThesisExperimentResult& result);

/// The per-entry experiments: the entries [i, j] (1-based), {method: {"mae", "std", "bias",
/// "count", "failures"}}, the table and CSV (entries named prefix + i + j: "m11", "x12").
nlohmann::json entries_json(const EntryExperimentResult& result);
nlohmann::json entry_methods_json(const EntryExperimentResult& result);
std::string entry_name(const std::string& prefix, Eigen::Index i, Eigen::Index j);
std::string entry_table(const EntryExperimentResult& result, const std::string& entry_prefix);
std::string entry_csv(const EntryExperimentResult& result, const std::string& entry_prefix);

/// The 2x2 sweep: one CSV row per level and method; the mean absolute errors as a table.
std::string sweep_csv(const std::vector<double>& levels, double std_b, const std::vector<EntryExperimentResult>& results);
std::string sweep_table(const std::vector<double>& levels, const std::vector<EntryExperimentResult>& results);

/// The generator's settings in words ("m = 12 samples of 6 strut accelerations ...").
std::string describe(const hexapod::SimulationOptions& simulation);

}  // namespace spdfit::experiment::detail
