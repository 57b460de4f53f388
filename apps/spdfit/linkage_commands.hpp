// `spdfit linkage analyze`: its options and action, and the number formats of its report (CLI internal).
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "linkage_arguments.hpp"
#include "spdfit/format.hpp"
#include "spdfit/linkage/analysis.hpp"

namespace spdfit::cli {

/// The options of `spdfit linkage analyze` as parsed.
struct AnalyzeOptionsCli {
  std::string lengths, psi_range = "0:360", output;
  int points = 37;
  bool json = false;
};

/// Call linkage::analyze on the lengths and print the table.
void run_analyze(const AnalyzeOptionsCli& options);

/// Numbers for people: 6 significant digits, or 4 decimals; "-" for NaN.
inline std::string g(double value) { return std::isnan(value) ? "-" : format_number(value, Precision::Full); }
inline std::string f4(double value) {
  if (std::isnan(value)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

/// {"min", "max"} in degrees.
inline nlohmann::json range_json(const linkage::AngleRange& range) {
  return {{"min", degrees(range.min)}, {"max", degrees(range.max)}};
}

}  // namespace spdfit::cli
