#include "spdfit/linkage/freudenstein.hpp"

#include <cmath>
#include <limits>
#include <algorithm>
#include <stdexcept>

#include "linkage_format.hpp"

namespace spdfit::linkage {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kPi = 3.14159265358979323846;

// |c| may exceed R by rounding when the linkage is exactly at a dead point; a few ulps of slack
// keep such positions assemblable instead of dropping them.
constexpr double kAssemblySlack = 8 * std::numeric_limits<double>::epsilon();

}  // namespace

Eigen::Vector3d freudenstein_parameters(const FourBar& bar) {
  for (double a : {bar.a1, bar.a2, bar.a3, bar.a4}) {
    if (!(a > 0.0) || !std::isfinite(a)) {
      throw std::invalid_argument("link lengths must be positive and finite");
    }
  }
  // Eq. 3.4.
  return {(bar.a1 * bar.a1 + bar.a2 * bar.a2 + bar.a4 * bar.a4 - bar.a3 * bar.a3) / (2.0 * bar.a2 * bar.a4),
          bar.a1 / bar.a2, bar.a1 / bar.a4};
}

std::optional<FourBar> link_lengths(const Eigen::Vector3d& k, std::string* problem) {
  auto fail = [problem](const std::string& why) -> std::optional<FourBar> {
    if (problem) *problem = why;
    return std::nullopt;
  };
  if (!k.allFinite()) return fail("k is not finite");
  // Eq. 3.4 with a1 = 1. A negative a2 (or a4) is the same link turned through 180 degrees: the
  // synthesis then wants the input (output) dial zero shifted by 180 degrees.
  if (!(k(1) > 0.0)) {
    return fail("k2 = " + detail::format(k(1)) + (k(1) == 0.0 ? " gives an infinite" : " gives a negative") +
                " input link a2 = 1/k2: no real linkage (a negative a2 is the input link turned by 180 degrees: "
                "shift the input dial zero alpha by 180 degrees)");
  }
  if (!(k(2) > 0.0)) {
    return fail("k3 = " + detail::format(k(2)) + (k(2) == 0.0 ? " gives an infinite" : " gives a negative") +
                " output link a4 = 1/k3: no real linkage (a negative a4 is the output link turned by 180 degrees: "
                "shift the output dial zero beta by 180 degrees)");
  }
  FourBar bar;
  bar.a1 = 1.0;
  bar.a2 = 1.0 / k(1);
  bar.a4 = 1.0 / k(2);
  const double a3_squared = 1.0 + bar.a2 * bar.a2 + bar.a4 * bar.a4 - 2.0 * bar.a2 * bar.a4 * k(0);
  if (!(a3_squared > 0.0)) {
    return fail("a3^2 = 1 + a2^2 + a4^2 - 2 a2 a4 k1 = " + detail::format(a3_squared) +
                " <= 0: no real coupler length (eq. 3.4)");
  }
  bar.a3 = std::sqrt(a3_squared);
  return bar;
}

double freudenstein_residual(const Eigen::Vector3d& k, double psi, double phi) {
  return k(0) + k(1) * std::cos(phi) - k(2) * std::cos(psi) - std::cos(psi - phi);  // eq. 3.3
}

MatrixXd synthesis_matrix(const Eigen::Ref<const VectorXd>& psi, const Eigen::Ref<const VectorXd>& phi) {
  if (psi.size() != phi.size()) throw std::invalid_argument("synthesis_matrix: psi and phi differ in length");
  MatrixXd S(psi.size(), 3);
  for (Index i = 0; i < psi.size(); ++i) {
    S(i, 0) = 1.0;
    S(i, 1) = std::cos(phi(i));
    S(i, 2) = -std::cos(psi(i));
  }
  return S;
}

VectorXd synthesis_rhs(const Eigen::Ref<const VectorXd>& psi, const Eigen::Ref<const VectorXd>& phi) {
  if (psi.size() != phi.size()) throw std::invalid_argument("synthesis_rhs: psi and phi differ in length");
  VectorXd b(psi.size());
  for (Index i = 0; i < psi.size(); ++i) b(i) = std::cos(psi(i) - phi(i));
  return b;
}

std::optional<double> output_angle(const Eigen::Vector3d& k, double psi, int branch) {
  // Eq. 3.3 as a cos(phi) + b sin(phi) + c = 0.
  const double a = k(1) - std::cos(psi);
  const double b = -std::sin(psi);
  const double c = k(0) - k(2) * std::cos(psi);
  const double R = std::hypot(a, b);
  if (!(R > 0.0)) return std::nullopt;  // crank tip on the output pivot: phi undetermined
  double ratio = -c / R;
  if (std::abs(ratio) > 1.0 + kAssemblySlack || !std::isfinite(ratio)) return std::nullopt;
  ratio = std::max(-1.0, std::min(1.0, ratio));
  return wrap_angle(std::atan2(b, a) + (branch >= 0 ? 1.0 : -1.0) * std::acos(ratio));
}

double freudenstein_dphi(const Eigen::Vector3d& k, double psi, double phi) {
  return -k(1) * std::sin(phi) - std::sin(psi - phi);  // notes 3.6.1
}

double freudenstein_dpsi(const Eigen::Vector3d& k, double psi, double phi) {
  return k(2) * std::sin(psi) + std::sin(psi - phi);
}

double wrap_angle(double x) { return x - 2.0 * kPi * std::round(x / (2.0 * kPi)); }

}  // namespace spdfit::linkage
