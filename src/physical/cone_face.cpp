// The face solve: the criterion minimized over the pseudo-inertias of given ranks r_k,
// P_k = L_k L_k^T with L_k 4 x r_k (a Burer-Monteiro factorization: every such P_k is in the cone,
// so there is no constraint left), the nonnegative scalars that are not at their bound, and the
// free parameters. Newton's method converges quadratically there, where the barrier path near a
// rank-deficient minimizer crawls; the result is a KKT point of the constrained problem exactly
// when the gradient's multipliers Z_k are positive semidefinite and those of the fixed scalars
// non-negative, which is checked.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "physical/cone_solver.hpp"

namespace spdfit::physical::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Face {
  std::vector<int> rank;             // r_k of each body
  std::vector<int> offset;           // where L_k starts in x
  std::vector<int> free_scalars;     // parameter indices of the nonnegative scalars not at their bound
  int first_scalar = 0;              // where they start in x
  int first_free = 0;                // where the free parameters start in x
  int size = 0;
};

Eigen::Map<const Eigen::MatrixXd> factor(const Face& face, const Eigen::VectorXd& x, int k) {
  return {x.data() + face.offset[static_cast<std::size_t>(k)], 4, face.rank[static_cast<std::size_t>(k)]};
}

Eigen::VectorXd theta_of(const ConeLayout& layout, const Face& face, const Eigen::VectorXd& x) {
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(layout.size());
  for (int k = 0; k < layout.bodies; ++k) {
    const auto L = factor(face, x, k);
    set_body_matrix(L * L.transpose(), theta, k);
  }
  for (std::size_t j = 0; j < face.free_scalars.size(); ++j)
    theta(face.free_scalars[j]) = x(face.first_scalar + static_cast<int>(j));
  theta.tail(layout.free) = x.tail(layout.free);
  return theta;
}

bool feasible(const Face& face, const Eigen::VectorXd& x) {
  for (std::size_t j = 0; j < face.free_scalars.size(); ++j)
    if (!(x(face.first_scalar + static_cast<int>(j)) > 0.0)) return false;
  return true;
}

// f, its gradient and Hessian in x (chain rule through theta(x)).
bool evaluate_face(const Criterion& f, const ConeLayout& layout, const Face& face, const Eigen::VectorXd& x, int order,
                   double& value, Eigen::VectorXd& g, Eigen::MatrixXd& H) {
  const Eigen::VectorXd theta = theta_of(layout, face, x);
  Evaluation ev;
  if (!f.evaluate(theta, order, ev)) return false;
  value = ev.f;
  if (order < 1) return true;
  // J: d theta / d x. Entry (i, l) of L_k moves P_k by e_i L_l^T + L_l e_i^T.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(layout.size(), face.size);
  for (int k = 0; k < layout.bodies; ++k) {
    const auto L = factor(face, x, k);
    const int r = face.rank[static_cast<std::size_t>(k)], at = face.offset[static_cast<std::size_t>(k)];
    for (int l = 0; l < r; ++l)
      for (int i = 0; i < 4; ++i) {
        Eigen::Matrix4d dP = Eigen::Matrix4d::Zero();
        dP.row(i) += L.col(l).transpose();
        dP.col(i) += L.col(l);
        for (int a = 0; a < kBodyCoordinates; ++a) J(kBodyCoordinates * k + a, at + i + 4 * l) = coordinate(dP, a);
      }
  }
  for (std::size_t j = 0; j < face.free_scalars.size(); ++j)
    J(face.free_scalars[j], face.first_scalar + static_cast<int>(j)) = 1.0;
  for (int j = 0; j < layout.free; ++j) J(layout.free_begin() + j, face.first_free + j) = 1.0;
  g = J.transpose() * ev.g;
  if (order < 2) return true;
  H = J.transpose() * ev.H * J;
  // The curvature of P_k = L_k L_k^T itself: 2 <Z_k, dL dL^T>, Z_k = df/dP_k.
  for (int k = 0; k < layout.bodies; ++k) {
    Eigen::Matrix4d Z = Eigen::Matrix4d::Zero();
    for (int a = 0; a < kBodyCoordinates; ++a) Z += ev.g(kBodyCoordinates * k + a) * basis_matrix(a);
    const int r = face.rank[static_cast<std::size_t>(k)], at = face.offset[static_cast<std::size_t>(k)];
    for (int l = 0; l < r; ++l)
      for (int i = 0; i < 4; ++i)
        for (int i2 = 0; i2 < 4; ++i2) H(at + i + 4 * l, at + i2 + 4 * l) += 2.0 * Z(i, i2);
  }
  H = 0.5 * (H + H.transpose()).eval();
  return true;
}

}  // namespace

std::optional<SolveResult> solve_on_face(const Criterion& f, const ConeLayout& layout, const Eigen::VectorXd& guess,
                                         int max_steps, int* steps_taken) {
  int steps = 0;
  if (steps_taken) *steps_taken = 0;
  if (!guess.allFinite()) return std::nullopt;
  // The face: each P_k's eigenvalues above the guess threshold, and the scalars above it.
  Face face;
  std::vector<Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>> eig;
  double largest = 0.0;
  for (int k = 0; k < layout.bodies; ++k) {
    eig.emplace_back(body_matrix(guess, k));
    const Eigen::Vector4d d = eig.back().eigenvalues();
    if (!(d.maxCoeff() > 0.0)) return std::nullopt;
    largest = std::max(largest, d.maxCoeff());
    face.offset.push_back(face.size);
    face.rank.push_back(static_cast<int>((d.array() > kActiveGuess * d.maxCoeff()).count()));
    face.size += 4 * face.rank.back();
  }
  double scale = largest;
  if (layout.bodies == 0) {
    for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j) scale = std::max(scale, guess(j));
  }
  face.first_scalar = face.size;
  for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j)
    if (guess(j) > kActiveGuess * scale) face.free_scalars.push_back(j);
  face.size += static_cast<int>(face.free_scalars.size());
  face.first_free = face.size;
  face.size += layout.free;

  Eigen::VectorXd x(face.size);
  for (int k = 0; k < layout.bodies; ++k) {
    const Eigen::Vector4d d = eig[static_cast<std::size_t>(k)].eigenvalues();
    const int r = face.rank[static_cast<std::size_t>(k)], at = face.offset[static_cast<std::size_t>(k)];
    for (int l = 0; l < r; ++l)
      x.segment<4>(at + 4 * l) = eig[static_cast<std::size_t>(k)].eigenvectors().col(3 - l) * std::sqrt(d(3 - l));
  }
  for (std::size_t j = 0; j < face.free_scalars.size(); ++j)
    x(face.first_scalar + static_cast<int>(j)) = guess(face.free_scalars[j]);
  x.tail(layout.free) = guess.tail(layout.free);

  double value = 0.0, value_next = 0.0;
  Eigen::VectorXd g, g_next;
  Eigen::MatrixXd H, H_next;
  Eigen::LLT<Eigen::MatrixXd> llt(face.size);
  int at_rounding = 0;
  bool converged = false;
  for (;;) {
    if (!evaluate_face(f, layout, face, x, 2, value, g, H)) return std::nullopt;
    // Levenberg-Marquardt: the gauge L -> L Q makes H singular; the smallest shift that makes it
    // definite leaves those directions alone (the gradient has no component along them).
    const double scale_h = std::max(H.diagonal().cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
    double shift = 1e-12 * scale_h;
    for (;;) {
      Eigen::MatrixXd Hs = H;
      Hs.diagonal().array() += shift;
      llt.compute(Hs);
      if (llt.info() == Eigen::Success && (llt.matrixLLT().diagonal().array() > 0.0).all()) break;
      shift *= 10.0;
      if (!(shift < 1e12 * scale_h)) return std::nullopt;
    }
    const Eigen::VectorXd step = -llt.solve(g);
    const double decrement = -g.dot(step);
    const double rounding = kRoundingMultiple * kEps * std::abs(value);
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
      const Eigen::VectorXd next = x + alpha * step;
      if (!feasible(face, next)) continue;
      if (!evaluate_face(f, layout, face, next, 0, value_next, g_next, H_next)) continue;
      if (value_next <= value - kArmijo * alpha * decrement ||
          (alpha * decrement <= rounding && value_next <= value + rounding)) {
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
  // eigenvalues of Z_k and the gradient at the fixed scalars, are not negative.
  SolveResult out;
  out.theta = theta_of(layout, face, x);
  out.iterations = steps;
  out.converged = true;
  out.f = value;
  const ConeCertificate c = kkt_certificate(f, layout, out.theta);
  if (!(c.dual_min_eig >= -kDualTolerance)) return std::nullopt;
  return out;
}

}  // namespace spdfit::physical::detail
