// Four-bar linkages with known answers for the linkage tests.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/freudenstein.hpp"
#include "test_support.hpp"

namespace spdfit::test {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDeg = kPi / 180.0;

/// A named linkage of a known Grashof type (a1 = 1 so that k gives these lengths back).
struct KnownLinkage {
  std::string name;
  linkage::FourBar bar;
  linkage::GrashofType type;
};

inline std::vector<KnownLinkage> known_linkages() {
  using linkage::GrashofType;
  return {
      {"crank-rocker", {1.0, 0.4, 1.1, 0.9}, GrashofType::CrankRocker},
      {"double-crank", {1.0, 2.0, 2.2, 1.8}, GrashofType::DoubleCrank},
      {"rocker-crank", {1.0, 0.9, 1.1, 0.4}, GrashofType::RockerCrank},
      {"double-rocker", {1.0, 0.9, 0.4, 1.1}, GrashofType::DoubleRocker},
      {"triple-rocker", {1.0, 0.75, 0.5, 0.7}, GrashofType::TripleRocker},
  };
}

/// An input range [lo, hi] (radians) the linkage sweeps on one branch without a dead point:
/// `fraction` of a turn for a crank input, else the middle `fraction` of an interval between dead
/// points.
inline std::pair<double, double> sweep_range(const linkage::FourBar& bar, double fraction = 0.8) {
  const std::vector<double> dead = linkage::dead_points(bar);
  if (dead.empty()) return {0.1, 0.1 + 2 * kPi * fraction};
  // Dead points come in +-pairs; the assemblable interval is around 0 or around pi.
  std::vector<double> ends = dead;
  ends.push_back(dead.front() + 2 * kPi);
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    const double mid = 0.5 * (ends[i] + ends[i + 1]);
    if (!std::isnan(linkage::transmission_angle(bar, mid))) {
      const double half = 0.5 * fraction * (ends[i + 1] - ends[i]);
      return {mid - half, mid + half};
    }
  }
  return {0.0, 0.0};
}

/// m input angles over the sweep and the linkage's outputs on `branch`: exact pairs.
inline void exact_pairs(const linkage::FourBar& bar, int branch, int m, VectorXd& psi, VectorXd& phi,
                        double fraction = 0.8) {
  const auto [lo, hi] = sweep_range(bar, fraction);
  const Eigen::Vector3d k = linkage::freudenstein_parameters(bar);
  psi.resize(m);
  phi.resize(m);
  for (int i = 0; i < m; ++i) {
    psi(i) = lo + (hi - lo) * i / (m - 1);
    phi(i) = *linkage::output_angle(k, psi(i), branch);
  }
}

}  // namespace spdfit::test
