// The face solve of physical identification: the criterion minimized over the pseudo-inertias of
// a given rank r, P = L L^T with L 4 x r (a Burer-Monteiro factorization: every such P is in the
// cone, so there is no constraint left), and the strut masses that are not at their bound.
// Newton's method converges quadratically there, where the barrier path near a rank-deficient
// minimizer crawls; the result is a KKT point of the constrained problem exactly when the
// gradient's multiplier Z is positive semidefinite, which is checked.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hexapod/physical_solver.hpp"

namespace spdfit::hexapod::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The multipliers of the active constraints must be >= -kDualTolerance (dimensionless, as the
// certificate's dual_min_eig): rounding is ~1e-14 there, a wrong face gives O(1e-3) and more.
constexpr double kDualTolerance = 1e-9;

// At most 4 x 4 entries of L and 6 strut masses.
using FaceVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 22, 1>;
using FaceMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 22, 22>;
using Factor = Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::ColMajor, 4, 4>;

struct Face {
  int rank = 4;
  std::vector<int> free_struts;  // parameter indices of the strut masses not at their bound
};

// theta of x = [vec(L); free strut masses].
ParamVector theta_of(const PhysicalModel& model, const Face& face, const FaceVector& x) {
  const Eigen::Map<const Factor> L(x.data(), 4, face.rank);
  ParamVector theta = ParamVector::Zero(model.parameters);
  set_pseudo_inertia(L * L.transpose(), theta);
  for (std::size_t k = 0; k < face.free_struts.size(); ++k) theta(face.free_struts[k]) = x(4 * face.rank + static_cast<int>(k));
  return theta;
}

bool feasible(const Face& face, const FaceVector& x) {
  for (std::size_t k = 0; k < face.free_struts.size(); ++k)
    if (!(x(4 * face.rank + static_cast<int>(k)) > 0.0)) return false;
  return true;
}

// f, its gradient and Hessian in x (chain rule through theta(x)).
bool evaluate_face(const PhysicalData& data, const PhysicalModel& model, const Face& face, const FaceVector& x,
                   int order, double& f, FaceVector& g, FaceMatrix& H) {
  const ParamVector theta = theta_of(model, face, x);
  Evaluation ev;
  if (!evaluate(data, model, theta, order, ev)) return false;
  f = ev.f;
  if (order < 1) return true;
  const int r = face.rank, nl = 4 * r, nx = static_cast<int>(x.size());
  const Eigen::Map<const Factor> L(x.data(), 4, r);
  // J: d theta / d x. Entry (k, l) of L moves P by e_k L_l^T + L_l e_k^T.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxPhysicalParameters, 22> J =
      Eigen::MatrixXd::Zero(model.parameters, nx);
  for (int l = 0; l < r; ++l)
    for (int k = 0; k < 4; ++k) {
      Eigen::Matrix4d dP = Eigen::Matrix4d::Zero();
      dP.row(k) += L.col(l).transpose();
      dP.col(k) += L.col(l);
      for (int a = 0; a < kPayloadParameters; ++a) J(a, k + 4 * l) = coordinate(dP, a);
    }
  for (std::size_t k = 0; k < face.free_struts.size(); ++k) J(face.free_struts[k], nl + static_cast<int>(k)) = 1.0;
  g = J.transpose() * ev.g;
  if (order < 2) return true;
  H = J.transpose() * ev.H * J;
  // The curvature of P = L L^T itself: 2 <Z, dL dL^T>, Z = df/dP.
  Eigen::Matrix4d Z = Eigen::Matrix4d::Zero();
  for (int a = 0; a < kPayloadParameters; ++a) Z += ev.g(a) * basis_matrix(a);
  for (int l = 0; l < r; ++l)
    for (int k = 0; k < 4; ++k)
      for (int k2 = 0; k2 < 4; ++k2) H(k + 4 * l, k2 + 4 * l) += 2.0 * Z(k, k2);
  H = 0.5 * (H + H.transpose()).eval();
  return true;
}

}  // namespace

std::optional<SolveResult> solve_on_face(const PhysicalData& data, const PhysicalModel& model,
                                         const ParamVector& guess, int max_steps, int* steps_taken) {
  int steps = 0;
  if (steps_taken) *steps_taken = 0;
  // The face: P's eigenvalues above the guess threshold, and the strut masses above it.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(scaled_pseudo_inertia(guess));
  const Eigen::Vector4d d = eig.eigenvalues();
  const double largest = d.maxCoeff();
  if (!(largest > 0.0)) return std::nullopt;
  Face face;
  face.rank = static_cast<int>((d.array() > kActiveGuess * largest).count());
  for (int a = kPayloadParameters; a < model.parameters; ++a)
    if (guess(a) > kActiveGuess * largest) face.free_struts.push_back(a);
  const int nl = 4 * face.rank, nx = nl + static_cast<int>(face.free_struts.size());
  FaceVector x(nx);
  {
    Eigen::Map<Factor> L(x.data(), 4, face.rank);
    for (int l = 0; l < face.rank; ++l) L.col(l) = eig.eigenvectors().col(3 - l) * std::sqrt(d(3 - l));
    for (std::size_t k = 0; k < face.free_struts.size(); ++k) x(nl + static_cast<int>(k)) = guess(face.free_struts[k]);
  }

  double f = 0.0, f_next = 0.0;
  FaceVector g, g_next;
  FaceMatrix H, H_next;
  Eigen::LLT<FaceMatrix> llt(nx);
  int at_rounding = 0;
  bool converged = false;
  for (;;) {
    if (!evaluate_face(data, model, face, x, 2, f, g, H)) return std::nullopt;
    // Levenberg-Marquardt: the gauge L -> L Q makes H singular; the smallest shift that makes it
    // definite leaves those directions alone (the gradient has no component along them).
    const double scale = std::max(H.diagonal().cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
    double shift = 1e-12 * scale;
    for (;;) {
      FaceMatrix Hs = H;
      Hs.diagonal().array() += shift;
      llt.compute(Hs);
      if (llt.info() == Eigen::Success && (llt.matrixLLT().diagonal().array() > 0.0).all()) break;
      shift *= 10.0;
      if (!(shift < 1e12 * scale)) return std::nullopt;
    }
    const FaceVector step = -llt.solve(g);
    const double decrement = -g.dot(step);
    const double rounding = kRoundingMultiple * kEps * std::abs(f);
    if (!std::isfinite(decrement)) return std::nullopt;
    at_rounding = decrement <= rounding ? at_rounding + 1 : 0;
    if (decrement <= kFinalDecrement || at_rounding > kRoundingSteps) {
      converged = true;
      break;
    }
    if (steps >= max_steps) break;
    ++steps;
    bool accepted = false;
    for (double alpha = 1.0; alpha >= kMinStep; alpha *= 0.5) {
      const FaceVector next = x + alpha * step;
      if (!feasible(face, next)) continue;
      if (!evaluate_face(data, model, face, next, 0, f_next, g_next, H_next)) continue;
      if (f_next <= f - kArmijo * alpha * decrement || (alpha * decrement <= rounding && f_next <= f + rounding)) {
        x = next;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      converged = decrement <= 1e3 * rounding;
      break;
    }
  }
  if (steps_taken) *steps_taken = steps;
  if (!converged) return std::nullopt;

  // A KKT point of the constrained problem: the multipliers of the active constraints, the
  // eigenvalues of Z and the gradient at the fixed strut masses, are not negative.
  SolveResult out;
  out.theta = theta_of(model, face, x);
  out.iterations = steps;
  out.converged = true;
  out.f = f;
  const PhysicalCertificate c = kkt_certificate(data, model, out.theta);
  if (!(c.dual_min_eig >= -kDualTolerance)) return std::nullopt;
  return out;
}

}  // namespace spdfit::hexapod::detail
