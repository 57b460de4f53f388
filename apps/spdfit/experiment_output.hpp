// Formatting Monte Carlo experiments for people (tables), programs (JSON) and plots (CSV), and
// progress on a terminal. Shared by `spdfit experiment` and `spdfit demo`.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/thesis.hpp"

namespace spdfit::cli {

/// {"mean", "std", "median", "max", "min", "standard_error", "count", "failures"}.
nlohmann::json summary_json(const experiment::Summary& summary);

/// The thesis experiment's JSON contract: {"experiment": "thesis", "noise_var", "samples",
/// "trials", "seed", "signal_var", "distribution", "methods": {"spde": {summary}, ...}}.
nlohmann::json thesis_json(const experiment::ThesisExperimentResult& result);

/// The thesis experiment as a table of error statistics, one row per method.
std::string thesis_table(const experiment::ThesisExperimentResult& result);

/// One line comparing two methods trial by trial: "spde vs procrustes: ...".
std::string paired_line(const experiment::ThesisExperimentResult& result, Method a, Method b);

/// The per-trial errors as CSV: "trial,ls,procrustes,...", one row per trial.
std::string thesis_csv(const experiment::ThesisExperimentResult& result);

/// 1-based [i, j] pairs of the entries, as the papers name them (x11, x12, ...).
nlohmann::json entries_json(const experiment::EntryExperimentResult& result);

/// {"procrustes": {"mae": [...], "std": [...], "bias": [...], "count", "failures"}, ...}.
nlohmann::json entry_methods_json(const experiment::EntryExperimentResult& result);

/// One row per entry: the true value and, for each method, mean |error| and std of the error.
std::string entry_table(const experiment::EntryExperimentResult& result, const std::string& entry_prefix);

/// Per-entry statistics as CSV: "method,entry,true,mae,std,bias", one row per method and entry.
std::string entry_csv(const experiment::EntryExperimentResult& result, const std::string& entry_prefix);

/// The 2x2 sweep as CSV, one row per level and method:
/// "std_a,std_b,trials,method,failures,mae_x11,mae_x12,mae_x22,std_x11,...,bias_x22".
std::string sweep_csv(const std::vector<double>& levels, double std_b,
                      const std::vector<experiment::EntryExperimentResult>& results);

/// The sweep as a readable table: mean absolute error of each entry, per level and method.
std::string sweep_table(const std::vector<double>& levels,
                        const std::vector<experiment::EntryExperimentResult>& results);

/// A progress callback for MonteCarloOptions: the progress line of long runs (ProgressLine:
/// percent and time left, on a terminal, after a second, not with -q), cleared when the trials end.
std::function<void(std::size_t, std::size_t)> trials_progress(const GlobalOptions& global, const std::string& label);

}  // namespace spdfit::cli
