// Internal: numbers in the reports' text, beside spdfit/format.hpp's (one value).
#pragma once

#include <string>

#include <Eigen/Core>

#include "spdfit/format.hpp"

namespace spdfit::detail {

/// The entries of v with `digits` decimals, two spaces apart ("6.2300  6.2300  8.3300").
inline std::string fixed_values(const Eigen::VectorXd& v, int digits) {
  std::string out;
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? "  " : "") + format_fixed(v(i), digits);
  return out;
}

}  // namespace spdfit::detail
