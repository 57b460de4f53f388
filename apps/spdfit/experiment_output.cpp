#include "experiment_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <unistd.h>

#include "output.hpp"
#include "spdfit/format.hpp"
#include "progress_line.hpp"
#include "spdfit/io.hpp"

namespace spdfit::cli {

using nlohmann::json;

json summary_json(const experiment::Summary& s) {
  return {{"mean", number_json(s.mean)},
          {"std", number_json(s.std)},
          {"median", number_json(s.median)},
          {"max", number_json(s.max)},
          {"min", number_json(s.min)},
          {"standard_error", number_json(s.standard_error())},
          {"count", s.count},
          {"failures", s.failures}};
}

namespace {

// A method's label in the thesis experiment's outputs: its name, and the noise model it was fitted
// with when that is not none ("spd-tls/rest").
std::string method_label(const experiment::MethodErrors& m) {
  std::string label(to_string(m.method));
  if (m.noise != experiment::FitNoise::None) label += "/" + std::string(to_string(m.noise));
  return label;
}

}  // namespace

json thesis_json(const experiment::ThesisExperimentResult& result) {
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
  for (const experiment::MethodErrors& m : result.methods) {
    out["methods"][method_label(m)] = summary_json(m.summary);
  }
  return out;
}

std::string thesis_table(const experiment::ThesisExperimentResult& result) {
  std::ostringstream out;
  char line[200];
  // The method column: 11 wide, wider for labels with a noise model ("spd-tls/rest").
  int width = 11;
  for (const experiment::MethodErrors& m : result.methods) width = std::max(width, int(method_label(m).size()));
  std::snprintf(line, sizeof line, "%-*s %9s %9s %9s %9s %11s %9s\n", width, "method", "mean", "+- s.e.", "std",
                "median", "max", "failures");
  out << line;
  for (const experiment::MethodErrors& m : result.methods) {
    const experiment::Summary& s = m.summary;
    std::snprintf(line, sizeof line, "%-*s %9s %9s %9s %9s %11s %9zu\n", width, method_label(m).c_str(), format_fixed(s.mean).c_str(),
                  format_fixed(s.standard_error()).c_str(), format_fixed(s.std).c_str(), format_fixed(s.median).c_str(),
                  format_fixed(s.max).c_str(), s.failures);
    out << line;
  }
  return out.str();
}

std::string paired_line(const experiment::ThesisExperimentResult& result, Method a, Method b) {
  const experiment::PairedComparison c = result.compare(a, b);
  char line[240];
  std::snprintf(
      line, sizeof line,
      "%s - %s, trial by trial: mean difference %s +- %s (s.e.); %s lower in %.1f%% of %zu trials\n",
      std::string(to_string(a)).c_str(), std::string(to_string(b)).c_str(), format_fixed(c.mean_difference).c_str(),
      format_fixed(c.standard_error).c_str(), std::string(to_string(a)).c_str(), 100.0 * c.fraction_lower, c.count);
  return line;
}

std::string thesis_csv(const experiment::ThesisExperimentResult& result) {
  std::ostringstream out;
  out << "trial";
  for (const experiment::MethodErrors& m : result.methods) out << ',' << method_label(m);
  out << '\n';
  for (std::size_t k = 0; k < result.trials; ++k) {
    out << k;
    for (const experiment::MethodErrors& m : result.methods) out << ',' << io::format_double(m.errors[k]);
    out << '\n';
  }
  return out.str();
}

json entries_json(const experiment::EntryExperimentResult& result) {
  json out = json::array();
  for (const auto& [i, j] : result.entries) out.push_back({i + 1, j + 1});
  return out;
}

json entry_methods_json(const experiment::EntryExperimentResult& result) {
  json out = json::object();
  for (const experiment::EntryStatistics& s : result.methods) {
    out[std::string(to_string(s.method))] = {{"mae", vector_json(s.mae)},
                                             {"std", vector_json(s.std)},
                                             {"bias", vector_json(s.bias)},
                                             {"count", s.count},
                                             {"failures", s.failures}};
  }
  return out;
}

namespace {

std::string entry_name(const std::string& prefix, Eigen::Index i, Eigen::Index j) {
  return prefix + std::to_string(i + 1) + std::to_string(j + 1);
}

}  // namespace

std::string entry_table(const experiment::EntryExperimentResult& result, const std::string& entry_prefix) {
  std::ostringstream out;
  char cell[120];
  std::snprintf(cell, sizeof cell, "%-6s %8s", "entry", "true");
  out << cell;
  for (const experiment::EntryStatistics& s : result.methods) {
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
    for (const experiment::EntryStatistics& s : result.methods) {
      const auto k = static_cast<Eigen::Index>(e);
      std::snprintf(cell, sizeof cell, "   %12s %10s", format_fixed(s.mae(k)).c_str(), format_fixed(s.std(k)).c_str());
      out << cell;
    }
    out << '\n';
  }
  return out.str();
}

std::string entry_csv(const experiment::EntryExperimentResult& result, const std::string& entry_prefix) {
  std::ostringstream out;
  out << "method,entry,true,mae,std,bias\n";
  for (const experiment::EntryStatistics& s : result.methods) {
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
                      const std::vector<experiment::EntryExperimentResult>& results) {
  std::ostringstream out;
  out << "std_a,std_b,trials,method,failures";
  for (const char* statistic : {"mae", "std", "bias"})
    for (const char* entry : {"x11", "x12", "x22"}) out << ',' << statistic << '_' << entry;
  out << '\n';
  for (std::size_t l = 0; l < levels.size(); ++l) {
    for (const experiment::EntryStatistics& s : results[l].methods) {
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
                        const std::vector<experiment::EntryExperimentResult>& results) {
  std::ostringstream out;
  char cell[120];
  out << "mean absolute error\n";
  std::string names = "      ", entries = "std_a ";
  for (const experiment::EntryStatistics& s : results.front().methods) {
    std::snprintf(cell, sizeof cell, "   %-26s", std::string(to_string(s.method)).c_str());
    names += cell;
    entries += "        x11      x12      x22";
  }
  names.erase(names.find_last_not_of(' ') + 1);
  out << names << '\n' << entries << '\n';
  for (std::size_t l = 0; l < levels.size(); ++l) {
    std::snprintf(cell, sizeof cell, "%5.2f ", levels[l]);
    out << cell;
    for (const experiment::EntryStatistics& s : results[l].methods) {
      std::snprintf(cell, sizeof cell, "   %8s %8s %8s", format_fixed(s.mae(0), 3).c_str(),
                    format_fixed(s.mae(1), 3).c_str(), format_fixed(s.mae(2), 3).c_str());
      out << cell;
    }
    out << '\n';
  }
  return out.str();
}

std::function<void(std::size_t, std::size_t)> trials_progress(const GlobalOptions& global, const std::string& label) {
  auto line = std::make_shared<std::optional<ProgressLine>>();
  line->emplace(global, label);
  ProgressCallback update = (*line)->callback();
  if (!update) return {};
  return [line, update](std::size_t done, std::size_t total) {
    if (!line->has_value()) return;
    if (done < total) {
      update(static_cast<double>(done) / static_cast<double>(total));
    } else {
      line->reset();  // cleared before the results are printed
    }
  };
}

}  // namespace spdfit::cli
