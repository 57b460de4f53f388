#include "dial_zeros.hpp"

#include <cmath>
#include <limits>

#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/design_error.hpp"
#include "spdfit/linkage/freudenstein.hpp"
#include "spdfit/linkage/structural_error.hpp"
#include "linkage_inputs.hpp"

namespace spdfit::linkage::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kPi = 3.14159265358979323846;
// The grid of starting dial zeros: fine enough that the start lies in the basin of the nearest
// minimum for ordinary prescribed functions, coarse enough to stay cheap (72 x 72 small QRs).
constexpr int kGridSteps = 72;  // 5 degrees

VectorXd plus(double offset, const VectorXd& v) { return (v.array() + offset).matrix(); }

DialZeroPoint unpack(const VectorXd& x) {
  DialZeroPoint p;
  p.k = x.head<3>();
  p.zeros = {x(3), x(4)};
  return p;
}

VectorXd pack(const DialZeroPoint& p) {
  VectorXd x(5);
  x << p.k, p.zeros.alpha, p.zeros.beta;
  return x;
}

}  // namespace

std::optional<std::pair<double, int>> structural_objective(const VectorXd& delta_psi, const VectorXd& delta_phi,
                                                           const VectorXd& weights, const DialZeroPoint& point) {
  if (!link_lengths(point.k)) return std::nullopt;
  const VectorXd psi = plus(point.zeros.alpha, delta_psi), phi = plus(point.zeros.beta, delta_phi);
  const auto branch = nearest_branch(point.k, psi, phi, weights);
  if (!branch) return std::nullopt;
  const VectorXd s = *structural_error(point.k, psi, phi, *branch);
  return std::make_pair(root_weights(weights, s.size()).cwiseProduct(s).squaredNorm(), *branch);
}

std::optional<DialZeroPoint> dial_zero_grid_start(const VectorXd& delta_psi, const VectorXd& delta_phi,
                                                  const VectorXd& weights, double threshold) {
  std::optional<DialZeroPoint> best;
  bool best_has_dead_point = true;
  double best_objective = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kGridSteps; ++i) {
    for (int j = 0; j < kGridSteps; ++j) {
      DialZeroPoint p;
      p.zeros = {2.0 * kPi * i / kGridSteps - kPi, 2.0 * kPi * j / kGridSteps - kPi};
      const VectorXd psi = plus(p.zeros.alpha, delta_psi), phi = plus(p.zeros.beta, delta_phi);
      p.k = design_error_synthesis(psi, phi, weights, threshold).k;
      const auto objective = structural_objective(delta_psi, delta_phi, weights, p);
      if (!objective) continue;
      const bool has_dead_point = !check_motion(*link_lengths(p.k), psi, phi, objective->second).dead_points.empty();
      // Linkages that can sweep the whole range first, then the smaller structural error.
      if ((best_has_dead_point && !has_dead_point) ||
          (has_dead_point == best_has_dead_point && objective->first < best_objective)) {
        best = p;
        best_objective = objective->first;
        best_has_dead_point = has_dead_point;
      }
    }
  }
  return best;
}

DialZeroFit fit_design_dial_zeros(const VectorXd& delta_psi, const VectorXd& delta_phi, const VectorXd& weights,
                                  const DialZeroPoint& start, const GaussNewtonSettings& settings) {
  const VectorXd root_w = root_weights(weights, delta_psi.size());
  const ResidualModel model = [&](const VectorXd& x, VectorXd& r, MatrixXd* J) {
    if (!x.allFinite()) return false;
    const DialZeroPoint p = unpack(x);
    const VectorXd psi = plus(p.zeros.alpha, delta_psi), phi = plus(p.zeros.beta, delta_phi);
    r.resize(psi.size());
    if (J) J->resize(psi.size(), 5);
    for (Index i = 0; i < psi.size(); ++i) {
      // Eq. 3.7: f = k1 + k2 cos(beta + dphi) - k3 cos(alpha + dpsi) - cos(alpha + dpsi - beta - dphi).
      r(i) = root_w(i) * freudenstein_residual(p.k, psi(i), phi(i));
      if (J) {
        J->row(i) << 1.0, std::cos(phi(i)), -std::cos(psi(i)), freudenstein_dpsi(p.k, psi(i), phi(i)),
            freudenstein_dphi(p.k, psi(i), phi(i));
        J->row(i) *= root_w(i);
      }
    }
    return true;
  };
  DialZeroFit fit;
  fit.gauss_newton = gauss_newton(model, pack(start), settings);
  fit.point = unpack(fit.gauss_newton.x);
  return fit;
}

DialZeroFit fit_structural_dial_zeros(const VectorXd& delta_psi, const VectorXd& delta_phi, const VectorXd& weights,
                                      const DialZeroPoint& start, int branch, const GaussNewtonSettings& settings) {
  const VectorXd root_w = root_weights(weights, delta_psi.size());
  const ResidualModel model = [&](const VectorXd& x, VectorXd& r, MatrixXd* J) {
    if (!x.allFinite()) return false;
    const DialZeroPoint p = unpack(x);
    if (!link_lengths(p.k)) return false;
    const VectorXd psi = plus(p.zeros.alpha, delta_psi), phi = plus(p.zeros.beta, delta_phi);
    const auto generated = generated_outputs(p.k, psi, phi, branch);
    if (!generated) return false;
    r = root_w.cwiseProduct(phi - *generated);
    if (J) {
      J->resize(psi.size(), 5);
      for (Index i = 0; i < psi.size(); ++i) {
        const double g = (*generated)(i);
        const double d = freudenstein_dphi(p.k, psi(i), g);
        // ds/dk = D^-1 S (eq. 3.16), ds/dalpha = -dphi_gen/dpsi = (df/dpsi)/(df/dphi), ds/dbeta = 1.
        J->row(i) << 1.0 / d, std::cos(g) / d, -std::cos(psi(i)) / d, freudenstein_dpsi(p.k, psi(i), g) / d, 1.0;
        J->row(i) *= root_w(i);
      }
    }
    return true;
  };
  DialZeroFit fit;
  fit.gauss_newton = gauss_newton(model, pack(start), settings);
  fit.point = unpack(fit.gauss_newton.x);
  return fit;
}

}  // namespace spdfit::linkage::detail
