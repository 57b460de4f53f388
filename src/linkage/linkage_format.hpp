// Numbers in the linkage messages (internal).
#pragma once

#include <cstdio>
#include <string>

#include "spdfit/format.hpp"

namespace spdfit::linkage::detail {

/// 6 significant digits: enough to recognize a value in a message, short enough to read.
inline std::string format(double value) { return format_number(value, Precision::Full); }

/// Radians shown as degrees, 4 decimals.
inline std::string degrees(double radians) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f deg", radians * 57.295779513082320876798);
  return buffer;
}

}  // namespace spdfit::linkage::detail
