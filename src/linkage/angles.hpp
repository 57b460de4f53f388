// Internal: degrees and radians, for the linkage files that convert between them.
#pragma once

namespace spdfit::linkage::detail {

inline constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

}  // namespace spdfit::linkage::detail
