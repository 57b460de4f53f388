#include "spdfit/linkage/grashof.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace spdfit::linkage {

namespace {
// s + l == p + q to this relative accuracy counts as a change point: lengths typed by hand or
// computed from exact ratios land within a few ulps of equality.
constexpr double kChangePointTolerance = 1e-12;
}  // namespace

const char* to_string(GrashofType type) {
  switch (type) {
    case GrashofType::CrankRocker: return "crank-rocker";
    case GrashofType::RockerCrank: return "rocker-crank";
    case GrashofType::DoubleCrank: return "double-crank";
    case GrashofType::DoubleRocker: return "double-rocker";
    case GrashofType::ChangePoint: return "change-point";
    case GrashofType::TripleRocker: return "triple-rocker";
  }
  return "?";
}

GrashofType grashof_type(const FourBar& bar) {
  const std::array<double, 4> a = {bar.a1, bar.a2, bar.a3, bar.a4};
  for (double x : a) {
    if (!(x > 0.0) || !std::isfinite(x)) throw std::invalid_argument("grashof_type: lengths must be positive and finite");
  }
  std::array<double, 4> sorted = a;
  std::sort(sorted.begin(), sorted.end());
  const double s_plus_l = sorted[0] + sorted[3];
  const double p_plus_q = sorted[1] + sorted[2];
  if (std::abs(s_plus_l - p_plus_q) <= kChangePointTolerance * p_plus_q) return GrashofType::ChangePoint;
  if (s_plus_l > p_plus_q) return GrashofType::TripleRocker;
  // Grashof: the shortest link turns fully relative to the others. Ties for the shortest cannot
  // occur here (two equal shortest links with s + l < p + q would need l < q).
  const auto shortest = std::min_element(a.begin(), a.end()) - a.begin();
  switch (shortest) {
    case 0: return GrashofType::DoubleCrank;
    case 1: return GrashofType::CrankRocker;
    case 2: return GrashofType::DoubleRocker;
    default: return GrashofType::RockerCrank;
  }
}

}  // namespace spdfit::linkage
