// Parsing the angle ranges and link lengths of the linkage commands (CLI only: no numerics).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace spdfit::cli {

/// "a:b" as two finite numbers (linkage::parse_angle_range); throws UsageError naming the option
/// (`option`: its library name, "psi_range") otherwise.
std::pair<double, double> parse_range(const std::string& text, const std::string& option);

/// "x1,x2,...,xn" as exactly `count` finite numbers; throws UsageError naming `option` otherwise.
std::vector<double> parse_list(const std::string& text, std::size_t count, const std::string& option);

/// Degrees to radians and back.
inline constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;
inline double radians(double degrees) { return degrees * kRadiansPerDegree; }
inline double degrees(double radians) { return radians / kRadiansPerDegree; }

}  // namespace spdfit::cli
