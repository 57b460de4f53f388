#include "render/experiment_render.hpp"

#include "spdfit/experiment/experiment_request.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "render/json_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/io.hpp"

namespace spdfit::experiment::detail {

using nlohmann::json;

using spdfit::detail::number_json;
using spdfit::detail::vector_json;

json summary_json(const Summary& s) {
  return {{"mean", number_json(s.mean)},
          {"std", number_json(s.std)},
          {"median", number_json(s.median)},
          {"max", number_json(s.max)},
          {"min", number_json(s.min)},
          {"standard_error", number_json(s.standard_error())},
          {"count", s.count},
          {"failures", s.failures}};
}

// A method's label in the thesis experiment's outputs: its name, and the noise model it was fitted
// with when that is not none ("spd-tls/rest").
std::string method_label(const MethodErrors& m) {
  std::string label(to_string(m.method));
  if (m.noise != FitNoise::None) label += "/" + std::string(to_string(m.noise));
  return label;
}

json thesis_json(const ThesisExperimentResult& result) {
  json out;
  out["experiment"] = "thesis";
  out["noise_var"] = result.options.simulation.noise_var;
  out["force_noise_var"] =
      result.options.simulation.force_noise_var.value_or(result.options.simulation.noise_var);
  out["samples"] = result.options.simulation.samples;
  out["trials"] = result.trials;
  out["seed"] = result.seed;
  out["signal_var"] = result.options.simulation.signal_var;
  out["distribution"] = std::string(hexapod::to_string(result.options.simulation.distribution));
  out["methods"] = json::object();
  for (const MethodErrors& m : result.methods) {
    out["methods"][method_label(m)] = summary_json(m.summary);
  }
  return out;
}

std::string thesis_table(const ThesisExperimentResult& result) {
  std::ostringstream out;
  char line[200];
  // The method column: 11 wide, wider for labels with a noise model ("spd-tls/rest").
  int width = 11;
  for (const MethodErrors& m : result.methods) width = std::max(width, int(method_label(m).size()));
  std::snprintf(line, sizeof line, "%-*s %9s %9s %9s %9s %11s %9s\n", width, "method", "mean", "+- s.e.", "std",
                "median", "max", "failures");
  out << line;
  for (const MethodErrors& m : result.methods) {
    const Summary& s = m.summary;
    std::snprintf(line, sizeof line, "%-*s %9s %9s %9s %9s %11s %9zu\n", width, method_label(m).c_str(), format_fixed(s.mean).c_str(),
                  format_fixed(s.standard_error()).c_str(), format_fixed(s.std).c_str(), format_fixed(s.median).c_str(),
                  format_fixed(s.max).c_str(), s.failures);
    out << line;
  }
  return out.str();
}

std::string paired_line(const ThesisExperimentResult& result, Method a, Method b) {
  const PairedComparison c = result.compare(a, b);
  char line[240];
  std::snprintf(
      line, sizeof line,
      "%s - %s, trial by trial: mean difference %s +- %s (s.e.); %s lower in %.1f%% of %zu trials\n",
      std::string(to_string(a)).c_str(), std::string(to_string(b)).c_str(), format_fixed(c.mean_difference).c_str(),
      format_fixed(c.standard_error).c_str(), std::string(to_string(a)).c_str(), 100.0 * c.fraction_lower, c.count);
  return line;
}

std::string thesis_csv(const ThesisExperimentResult& result) {
  std::ostringstream out;
  out << "trial";
  for (const MethodErrors& m : result.methods) out << ',' << method_label(m);
  out << '\n';
  for (std::size_t k = 0; k < result.trials; ++k) {
    out << k;
    for (const MethodErrors& m : result.methods) out << ',' << io::format_double(m.errors[k]);
    out << '\n';
  }
  return out.str();
}

json entries_json(const EntryExperimentResult& result) {
  json out = json::array();
  for (const auto& [i, j] : result.entries) out.push_back({i + 1, j + 1});
  return out;
}

json entry_methods_json(const EntryExperimentResult& result) {
  json out = json::object();
  for (const EntryStatistics& s : result.methods) {
    out[std::string(to_string(s.method))] = {{"mae", vector_json(s.mae)},
                                             {"std", vector_json(s.std)},
                                             {"bias", vector_json(s.bias)},
                                             {"count", s.count},
                                             {"failures", s.failures}};
  }
  return out;
}

std::string entry_name(const std::string& prefix, Eigen::Index i, Eigen::Index j) {
  return prefix + std::to_string(i + 1) + std::to_string(j + 1);
}

std::string entry_table(const EntryExperimentResult& result, const std::string& entry_prefix) {
  std::ostringstream out;
  char cell[120];
  std::snprintf(cell, sizeof cell, "%-6s %8s", "entry", "true");
  out << cell;
  for (const EntryStatistics& s : result.methods) {
    const std::string name(to_string(s.method));
    std::snprintf(cell, sizeof cell, "   %12s %10s", (name + " |e|").c_str(), "std e");
    out << cell;
  }
  out << '\n';
  for (std::size_t e = 0; e < result.entries.size(); ++e) {
    const auto [i, j] = result.entries[e];
    std::snprintf(cell, sizeof cell, "%-6s %8s", entry_name(entry_prefix, i, j).c_str(),
                  format_fixed(result.truth(i, j)).c_str());
    out << cell;
    for (const EntryStatistics& s : result.methods) {
      const auto k = static_cast<Eigen::Index>(e);
      std::snprintf(cell, sizeof cell, "   %12s %10s", format_fixed(s.mae(k)).c_str(), format_fixed(s.std(k)).c_str());
      out << cell;
    }
    out << '\n';
  }
  return out.str();
}

std::string entry_csv(const EntryExperimentResult& result, const std::string& entry_prefix) {
  std::ostringstream out;
  out << "method,entry,true,mae,std,bias\n";
  for (const EntryStatistics& s : result.methods) {
    for (std::size_t e = 0; e < result.entries.size(); ++e) {
      const auto [i, j] = result.entries[e];
      const auto k = static_cast<Eigen::Index>(e);
      out << to_string(s.method) << ',' << entry_name(entry_prefix, i, j) << ','
          << io::format_double(result.truth(i, j)) << ',' << io::format_double(s.mae(k)) << ','
          << io::format_double(s.std(k)) << ',' << io::format_double(s.bias(k)) << '\n';
    }
  }
  return out.str();
}

std::string sweep_csv(const std::vector<double>& levels, double std_b,
                      const std::vector<EntryExperimentResult>& results) {
  std::ostringstream out;
  out << "std_a,std_b,trials,method,failures";
  for (const char* statistic : {"mae", "std", "bias"})
    for (const char* entry : {"x11", "x12", "x22"}) out << ',' << statistic << '_' << entry;
  out << '\n';
  for (std::size_t l = 0; l < levels.size(); ++l) {
    for (const EntryStatistics& s : results[l].methods) {
      out << io::format_double(levels[l]) << ',' << io::format_double(std_b) << ',' << results[l].trials
          << ',' << to_string(s.method) << ',' << s.failures;
      for (const Eigen::VectorXd* v : {&s.mae, &s.std, &s.bias})
        for (Eigen::Index e = 0; e < v->size(); ++e) out << ',' << io::format_double((*v)(e));
      out << '\n';
    }
  }
  return out.str();
}

std::string sweep_table(const std::vector<double>& levels,
                        const std::vector<EntryExperimentResult>& results) {
  std::ostringstream out;
  char cell[120];
  out << "mean absolute error\n";
  std::string names = "      ", entries = "std_a ";
  for (const EntryStatistics& s : results.front().methods) {
    std::snprintf(cell, sizeof cell, "   %-26s", std::string(to_string(s.method)).c_str());
    names += cell;
    entries += "        x11      x12      x22";
  }
  names.erase(names.find_last_not_of(' ') + 1);
  out << names << '\n' << entries << '\n';
  for (std::size_t l = 0; l < levels.size(); ++l) {
    std::snprintf(cell, sizeof cell, "%5.2f ", levels[l]);
    out << cell;
    for (const EntryStatistics& s : results[l].methods) {
      std::snprintf(cell, sizeof cell, "   %8s %8s %8s", format_fixed(s.mae(0), 3).c_str(),
                    format_fixed(s.mae(1), 3).c_str(), format_fixed(s.mae(2), 3).c_str());
      out << cell;
    }
    out << '\n';
  }
  return out.str();
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

}  // namespace spdfit::experiment::detail

namespace spdfit::experiment {

namespace {

// Whether the results include both methods (the reports compare them when they do).
template <typename Result>
bool reports_both(const Result& result, Method a, Method b) {
  bool found_a = false, found_b = false;
  for (const auto& m : result.methods) {
    found_a = found_a || m.method == a;
    found_b = found_b || m.method == b;
  }
  return found_a && found_b;
}

std::string thesis_report(const ThesisExperimentResult& result) {
  std::ostringstream out;
  out << "Thesis experiment (seed 000, chapter 6), M_p of eq. 6.1:\n"
      << detail::describe(result.options.simulation) << ".\n"
      << result.trials << " trials, seed " << result.seed << ". Error ||M_p - M_hat||_F:\n\n"
      << detail::thesis_table(result);
  if (reports_both(result, Method::Spde, Method::SymmetricProcrustes)) {
    out << '\n' << detail::paired_line(result, Method::Spde, Method::SymmetricProcrustes);
  }
  return out.str();
}

std::string paper_hexapod_report(const ExperimentRun& run) {
  const EntryExperimentResult& result = run.entries.front();
  std::ostringstream out;
  out << "The paper's hexapod experiment (seed 001, Figure 2), M_p of thesis eq. 6.1:\n"
      << detail::describe(run.paper_hexapod.simulation) << ".\n"
      << result.trials << " trials, seed " << result.seed
      << ". |e|: mean absolute error; std e: standard deviation of the error.\n\n"
      << detail::entry_table(result, "m");
  if (reports_both(result, Method::Spde, Method::SymmetricProcrustes)) {
    const EntryExperimentResult::Wins wins = result.wins(Method::Spde, Method::SymmetricProcrustes);
    out << '\n'
        << "spde has the smaller mean absolute error on " << wins.mae << " of " << wins.entries
        << " entries and the smaller standard deviation on " << wins.std << ".\n";
  }
  return out.str();
}

std::string paper_2x2_report(const ExperimentRun& run, const std::string& csv_path) {
  const Paper2x2Options& options = run.paper_2x2;
  std::ostringstream out;
  if (run.sweep) {
    if (csv_path.empty()) return to_csv(run);
    out << "The paper's 2x2 example (seed 001, Figure 3), std_b = " << options.std_b << ", " << run.trials
        << " trials per level, seed " << run.seed << "; table written to " << csv_path << ".\n\n"
        << detail::sweep_table(run.levels, run.entries);
    return out.str();
  }
  const EntryExperimentResult& result = run.entries.front();
  out << "The paper's 2x2 example (seed 001, Figure 3): std_a = " << options.std_a << ", std_b = " << options.std_b
      << "; " << result.trials << " trials, seed " << result.seed
      << ".\n|e|: mean absolute error; std e: standard deviation of the error.\n\n"
      << detail::entry_table(result, "x");
  return out.str();
}

nlohmann::json entry_experiment_json(const ExperimentRun& run) {
  nlohmann::json out;
  const EntryExperimentResult& result = run.entries.front();
  if (run.kind == ExperimentKind::PaperHexapod) {
    const hexapod::SimulationOptions& simulation = run.paper_hexapod.simulation;
    out["experiment"] = "paper-hexapod";
    out["noise_var"] = simulation.noise_var;
    out["force_noise_var"] = simulation.force_noise_var.value_or(simulation.noise_var);
    out["samples"] = simulation.samples;
    out["trials"] = result.trials;
    out["seed"] = result.seed;
    out["signal_var"] = simulation.signal_var;
    out["distribution"] = std::string(hexapod::to_string(simulation.distribution));
  } else {
    out["experiment"] = "paper-2x2";
    out["std_a"] = run.paper_2x2.std_a;
    out["std_b"] = run.paper_2x2.std_b;
    out["trials"] = result.trials;
    out["seed"] = result.seed;
  }
  out["entries"] = detail::entries_json(result);
  out["truth"] = spdfit::detail::matrix_json(result.truth);
  out["methods"] = detail::entry_methods_json(result);
  return out;
}

nlohmann::json sweep_json(const ExperimentRun& run) {
  nlohmann::json out;
  out["experiment"] = "paper-2x2";
  out["sweep"] = true;
  out["std_b"] = run.paper_2x2.std_b;
  out["trials"] = run.trials;
  out["seed"] = run.seed;
  out["entries"] = detail::entries_json(run.entries.front());
  out["levels"] = nlohmann::json::array();
  for (std::size_t l = 0; l < run.levels.size(); ++l) {
    out["levels"].push_back({{"std_a", run.levels[l]}, {"methods", detail::entry_methods_json(run.entries[l])}});
  }
  return out;
}

}  // namespace

std::string to_json(const ExperimentRun& run) {
  switch (run.kind) {
    case ExperimentKind::Thesis:
      return detail::thesis_json(*run.thesis).dump(2) + "\n";
    case ExperimentKind::PaperHexapod:
      return entry_experiment_json(run).dump(2) + "\n";
    case ExperimentKind::Paper2x2:
      return (run.sweep ? sweep_json(run) : entry_experiment_json(run)).dump(2) + "\n";
    case ExperimentKind::Physical:
      break;
  }
  return to_json(*run.physical);
}

std::string report(const ExperimentRun& run, const std::string& csv_path) {
  switch (run.kind) {
    case ExperimentKind::Thesis:
      return thesis_report(*run.thesis);
    case ExperimentKind::PaperHexapod:
      return paper_hexapod_report(run);
    case ExperimentKind::Paper2x2:
      return paper_2x2_report(run, csv_path);
    case ExperimentKind::Physical:
      break;
  }
  return report(*run.physical);
}

std::string to_csv(const ExperimentRun& run) {
  switch (run.kind) {
    case ExperimentKind::Thesis:
      return detail::thesis_csv(*run.thesis);
    case ExperimentKind::PaperHexapod:
      return detail::entry_csv(run.entries.front(), "m");
    case ExperimentKind::Paper2x2:
      return run.sweep ? detail::sweep_csv(run.levels, run.paper_2x2.std_b, run.entries)
                       : detail::entry_csv(run.entries.front(), "x");
    case ExperimentKind::Physical:
      break;
  }
  return {};
}

}  // namespace spdfit::experiment

