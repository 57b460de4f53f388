#include "spdfit/linkage/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "linkage_format.hpp"

namespace spdfit::linkage {

using Eigen::Index;
using Eigen::VectorXd;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
// As in output_angle: rounding may put an exact dead point a few ulps outside [-1, 1].
constexpr double kAssemblySlack = 8 * std::numeric_limits<double>::epsilon();

void check_lengths(const FourBar& bar) {
  for (double a : {bar.a1, bar.a2, bar.a3, bar.a4}) {
    if (!(a > 0.0) || !std::isfinite(a))
      throw std::invalid_argument("link lengths must be positive and finite");
  }
}

// cos(mu) before clamping: outside [-1, 1] where the linkage cannot be assembled.
double cos_transmission(const FourBar& bar, double psi) {
  const double e2 = bar.a1 * bar.a1 + bar.a2 * bar.a2 - 2.0 * bar.a1 * bar.a2 * std::cos(psi);
  return (bar.a3 * bar.a3 + bar.a4 * bar.a4 - e2) / (2.0 * bar.a3 * bar.a4);
}

bool assemblable(const FourBar& bar, double psi) {
  return std::abs(cos_transmission(bar, psi)) <= 1.0 + kAssemblySlack;
}

double clamped_acos(double c) { return std::acos(std::max(-1.0, std::min(1.0, c))); }

// Every angle base + 2 pi n in [lo, hi], the first `most` of them at most (a range may span
// 1e40 turns).
void copies_in(double base, double lo, double hi, std::vector<double>& out,
               std::size_t most = std::numeric_limits<std::size_t>::max()) {
  std::size_t added = 0;
  for (double n = std::ceil((lo - base) / kTwoPi); base + n * kTwoPi <= hi && added < most; n += 1.0, ++added)
    out.push_back(base + n * kTwoPi);
}

// The input angles in [lo, hi] at which mu can be extreme: the ends, the multiples of pi (cos psi
// extreme) and the dead points (edges of the assemblable intervals).
std::vector<double> extreme_candidates(const FourBar& bar, double lo, double hi) {
  std::vector<double> psi = {lo, hi};
  copies_in(0.0, lo, hi, psi);
  copies_in(kPi, lo, hi, psi);
  for (double d : dead_points(bar)) copies_in(d, lo, hi, psi);
  return psi;
}

}  // namespace

double transmission_angle(const FourBar& bar, double psi) {
  check_lengths(bar);
  const double c = cos_transmission(bar, psi);
  if (!(std::abs(c) <= 1.0 + kAssemblySlack)) return std::numeric_limits<double>::quiet_NaN();
  return clamped_acos(c);
}

std::vector<double> dead_points(const FourBar& bar) {
  check_lengths(bar);
  std::vector<double> out;
  // e = a3 + a4 (mu = pi) or e = |a3 - a4| (mu = 0), e^2 = a1^2 + a2^2 - 2 a1 a2 cos psi.
  for (double e : {bar.a3 + bar.a4, std::abs(bar.a3 - bar.a4)}) {
    const double u = (bar.a1 * bar.a1 + bar.a2 * bar.a2 - e * e) / (2.0 * bar.a1 * bar.a2);
    if (std::abs(u) > 1.0 + kAssemblySlack) continue;
    const double psi = clamped_acos(u);
    out.push_back(psi);
    if (psi > 0.0 && psi < kPi) out.push_back(-psi);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

AngleRange transmission_angle_range(const FourBar& bar, double psi_lo, double psi_hi) {
  check_lengths(bar);
  if (!(psi_lo <= psi_hi)) throw std::invalid_argument("transmission_angle_range: psi_lo > psi_hi");
  // mu is 2 pi-periodic in psi, so a turn or more of input attains every value of one turn; a
  // huge range (fuzzing found psi spanning 1e40 rad) would otherwise list a candidate per turn.
  if (psi_hi - psi_lo >= kTwoPi) {
    psi_lo = 0.0;
    psi_hi = kTwoPi;
  }
  AngleRange range{kPi, 0.0};
  for (double psi : extreme_candidates(bar, psi_lo, psi_hi)) {
    const double mu = clamped_acos(cos_transmission(bar, psi));
    range.min = std::min(range.min, mu);
    range.max = std::max(range.max, mu);
  }
  return range;
}

MotionCheck check_motion(const FourBar& bar, const Eigen::Ref<const VectorXd>& psi,
                         const Eigen::Ref<const VectorXd>& phi, int branch) {
  check_lengths(bar);
  if (psi.size() != phi.size() || psi.size() == 0)
    throw std::invalid_argument("check_motion: psi and phi must be non-empty, of equal length");
  MotionCheck check;
  check.grashof = grashof_type(bar);
  const double lo = psi.minCoeff(), hi = psi.maxCoeff();
  check.transmission = transmission_angle_range(bar, lo, hi);
  for (double d : dead_points(bar))
    copies_in(d, lo, hi, check.dead_points, MotionCheck::kMaxListedDeadPoints);
  std::sort(check.dead_points.begin(), check.dead_points.end());
  if (check.dead_points.size() > MotionCheck::kMaxListedDeadPoints) {
    check.dead_points.resize(MotionCheck::kMaxListedDeadPoints);
  }

  std::vector<std::string> reasons;
  if (!check.dead_points.empty()) {
    reasons.push_back("the input passes a dead point (coupler and output link in line) at psi = " +
                      detail::degrees(check.dead_points.front()) +
                      " within the prescribed range: it cannot turn through it, and beyond it only the other "
                      "assembly branch continues");
  } else if (!assemblable(bar, lo)) {
    reasons.push_back("the linkage cannot be assembled anywhere in the prescribed input range");
  }
  // Prescribed outputs that lie nearer to the other branch: the classic branch defect of
  // precision-point synthesis (some positions reached only on the other assembly).
  const Eigen::Vector3d k = freudenstein_parameters(bar);
  Index nearer_other = 0;
  double first_psi = 0.0;
  for (Index i = 0; i < psi.size(); ++i) {
    const auto on = output_angle(k, psi(i), branch), other = output_angle(k, psi(i), -branch);
    if (!on || !other) continue;
    if (std::abs(wrap_angle(phi(i) - *other)) < std::abs(wrap_angle(phi(i) - *on))) {
      if (nearer_other++ == 0) first_psi = psi(i);
    }
  }
  if (nearer_other > 0) {
    reasons.push_back(std::to_string(nearer_other) + " prescribed position(s), the first at psi = " +
                      detail::degrees(first_psi) + ", lie nearer to the other assembly branch");
  }
  check.branch_defect = !reasons.empty();
  for (std::size_t i = 0; i < reasons.size(); ++i) check.branch_defect_reason += (i ? "; " : "") + reasons[i];
  return check;
}

Analysis analyze(const FourBar& bar, const Eigen::Ref<const VectorXd>& psi) {
  check_lengths(bar);
  if (!psi.allFinite()) throw std::invalid_argument("analyze: the input angles must be finite");
  Analysis out;
  out.bar = bar;
  out.k = freudenstein_parameters(bar);
  out.grashof = grashof_type(bar);
  out.input_fully_rotates =
      bar.a1 + bar.a2 <= bar.a3 + bar.a4 && std::abs(bar.a1 - bar.a2) >= std::abs(bar.a3 - bar.a4);
  out.dead_points = dead_points(bar);

  std::optional<double> previous_plus, previous_minus;
  for (Index i = 0; i < psi.size(); ++i) {
    AnalysisSample sample;
    sample.psi = psi(i);
    // Each branch unwrapped along psi (2 pi shifts only), restarting after a gap.
    auto follow = [](std::optional<double> phi, std::optional<double>& previous) {
      if (phi && previous) phi = *previous + wrap_angle(*phi - *previous);
      previous = phi;
      return phi;
    };
    sample.phi_plus = follow(output_angle(out.k, psi(i), 1), previous_plus);
    sample.phi_minus = follow(output_angle(out.k, psi(i), -1), previous_minus);
    const double mu = transmission_angle(bar, psi(i));
    if (!std::isnan(mu)) sample.transmission_angle = mu;
    out.samples.push_back(sample);
  }
  if (psi.size() > 0) {
    AngleRange range{kPi, 0.0};
    bool any = false;
    for (double p : extreme_candidates(bar, psi.minCoeff(), psi.maxCoeff())) {
      if (!assemblable(bar, p)) continue;
      const double mu = clamped_acos(cos_transmission(bar, p));
      range.min = std::min(range.min, mu);
      range.max = std::max(range.max, mu);
      any = true;
    }
    if (any) out.transmission = range;
  }
  return out;
}

}  // namespace spdfit::linkage
