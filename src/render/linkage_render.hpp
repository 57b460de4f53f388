// Internal: the numbers of the linkage commands' reports and JSON (synthesize, analyze).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "linkage/angles.hpp"
#include "render/json_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/linkage/analysis.hpp"

namespace spdfit::linkage::detail {

inline double in_degrees(double radians) { return radians / kRadiansPerDegree; }
inline double in_radians(double degrees) { return degrees * kRadiansPerDegree; }

/// Numbers for people: 6 significant digits, or 4 decimals; "-" for NaN.
inline std::string full_g(double value) { return std::isnan(value) ? "-" : format_number(value, Precision::Full); }
inline std::string four_decimals(double value) {
  if (std::isnan(value)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}


/// {"min", "max"} in degrees.
inline nlohmann::json span_json(const AngleRange& range) {
  return {{"min", in_degrees(range.min)}, {"max", in_degrees(range.max)}};
}

}  // namespace spdfit::linkage::detail
