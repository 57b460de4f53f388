#include "spdfit/nearest_correlation.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "estimators/diagnostics.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

void check(const Eigen::Ref<const MatrixXd>& C, const NearestCorrelationOptions& o) {
  if (C.rows() == 0 || C.rows() != C.cols()) {
    throw std::invalid_argument("nearest_correlation: C must be a non-empty square matrix, not " +
                                std::to_string(C.rows()) + "x" + std::to_string(C.cols()));
  }
  if (!C.allFinite()) throw std::invalid_argument("nearest_correlation: C contains NaN or Inf");
  std::string error;
  if (!o.is_valid(C.rows(), &error)) throw std::invalid_argument("nearest_correlation: " + error);
}

// The dual of min ||X - G||_F^2 / 2 over X >= 0 with diag(X) = b (Qi & Sun 2006):
// theta(y) = ||(G + diag y)_+||_F^2 / 2 - b^T y, gradient F(y) = diag((G + diag y)_+) - b.
struct Dual {
  const MatrixXd& G;
  const VectorXd& b;
  MatrixXd P;      // eigenvectors of G + diag(y)
  VectorXd lambda;  // its eigenvalues, ascending
  double theta = 0.0;
  VectorXd F;

  // Evaluates theta at y; with vectors, also the eigenvectors and the gradient. False when the
  // eigensolver fails.
  bool evaluate(const VectorXd& y, bool vectors) {
    MatrixXd M = G;
    M.diagonal() += y;
    if (!detail::symmetric_eigen(M, lambda, vectors ? &P : nullptr)) return false;
    const VectorXd positive = lambda.cwiseMax(0.0);
    theta = 0.5 * positive.squaredNorm() - b.dot(y);
    if (vectors) {
      // diag(P diag(lambda_+) P^T)
      F = (P.array().square().matrix() * positive) - b;
    }
    return true;
  }
};

// The generalized Jacobian of F at the current eigendecomposition (Qi & Sun 2006, eq. (20)):
// V h = diag(P (Omega o (P^T diag(h) P)) P^T), with Omega_ij = 1 when lambda_i, lambda_j > 0,
// lambda_i / (lambda_i - lambda_j) when lambda_i > 0 >= lambda_j, 0 when both <= 0.
//
// With the r positive eigenvalues last (P = [P2 P1], P1 their eigenvectors) Omega has the blocks
// [0, Omega21; Omega12, 1], so with B = Omega12 o (P1^T diag(h) P2):
//   V h = diag(P1 (P1^T diag(h) P1) P1^T) + 2 diag(P1 B P2^T),
// O(n^2 r) instead of O(n^3). (Qi & Sun's complement form, O(n^2 (n - r)) for r > n/2, computes
// h - (...) and loses the semidefiniteness of V to cancellation; the conjugate gradients then
// stall, so it is not used.)
class Jacobian {
 public:
  explicit Jacobian(const Dual& dual) {
    const VectorXd& l = dual.lambda;
    const Index n = l.size();
    Index r = 0;
    while (r < n && l(n - 1 - r) > 0.0) ++r;
    P1_ = dual.P.rightCols(r);
    P2_ = dual.P.leftCols(n - r);
    omega12_.resize(r, n - r);
    for (Index j = 0; j < n - r; ++j) {
      for (Index i = 0; i < r; ++i) {
        const double li = l(n - r + i), lj = l(j);
        omega12_(i, j) = li / (li - lj);
      }
    }
    // The diagonal of V (Borsdorf & Higham's preconditioner): V_kk = sum_ij P_ki^2 Omega_ij P_kj^2,
    // a sum of non-negative terms (no cancellation).
    const MatrixXd Q1 = P1_.array().square().matrix(), Q2 = P2_.array().square().matrix();
    const VectorXd s1 = Q1.rowwise().sum();
    diagonal_ = s1.cwiseProduct(s1) + 2.0 * Q1.cwiseProduct(Q2 * omega12_.transpose()).rowwise().sum();
  }

  VectorXd apply(const VectorXd& h) const {
    const MatrixXd hP1 = h.asDiagonal() * P1_;
    const MatrixXd square = P1_.transpose() * hP1;  // P1^T diag(h) P1
    const MatrixXd B = omega12_.cwiseProduct(hP1.transpose() * P2_);
    return P1_.cwiseProduct(P1_ * square).rowwise().sum() + 2.0 * P1_.cwiseProduct(P2_ * B.transpose()).rowwise().sum();
  }

  const VectorXd& diagonal() const { return diagonal_; }

 private:
  MatrixXd P1_, P2_, omega12_;
  VectorXd diagonal_;
};

// Preconditioned conjugate gradients for (V + mu I) d = rhs, to a relative residual `tol`.
VectorXd pcg(const Jacobian& V, double mu, const VectorXd& rhs, double tol, int max_iterations) {
  const Index n = rhs.size();
  VectorXd d = VectorXd::Zero(n);
  VectorXd r = rhs;
  const VectorXd precondition = (V.diagonal().array() + mu).max(1e-12).inverse().matrix();
  VectorXd z = precondition.cwiseProduct(r);
  VectorXd p = z;
  double rz = r.dot(z);
  const double stop = tol * rhs.norm();
  for (int k = 0; k < max_iterations && r.norm() > stop; ++k) {
    const VectorXd w = V.apply(p) + mu * p;
    const double pw = p.dot(w);
    if (!(pw > 0.0)) break;
    const double step = rz / pw;
    d += step * p;
    r -= step * w;
    z = precondition.cwiseProduct(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return d;
}

}  // namespace

bool NearestCorrelationOptions::is_valid(Index n, std::string* error) const {
  auto fail = [error](std::string why) {
    if (error) *error = std::move(why);
    return false;
  };
  if (weights.size() != 0) {
    if (weights.size() != n) {
      return fail(std::to_string(weights.size()) + " weights for a " + std::to_string(n) + "x" + std::to_string(n) +
                  " matrix: give one per row");
    }
    for (Index i = 0; i < n; ++i) {
      if (!(weights(i) > 0.0) || !std::isfinite(weights(i))) {
        return fail("weight " + std::to_string(i + 1) + " is " + detail::format_number(weights(i)) +
                    ": weights must be finite and > 0");
      }
    }
  }
  if (!(alpha >= 0.0 && alpha < 1.0)) return fail("alpha must be in [0, 1)");
  if (max_iterations < 1) return fail("max_iterations must be >= 1");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) return fail("tolerance must be a finite number > 0");
  return true;
}

NearestCorrelationResult nearest_correlation(const Eigen::Ref<const MatrixXd>& C,
                                             const NearestCorrelationOptions& options) {
  check(C, options);
  const Index n = C.rows();
  NearestCorrelationResult out;
  const MatrixXd S = detail::symmetric_part(MatrixXd(C));
  const double asymmetry = (C - C.transpose()).norm();
  if (asymmetry > 1e-10 * std::max(C.norm(), std::numeric_limits<double>::min())) {
    out.warnings.push_back("C is not symmetric (||C - C^T||_F / ||C||_F = " +
                           detail::format_number(asymmetry / C.norm()) +
                           ", more than rounding): its symmetric part (C + C^T) / 2 was used; is it the right file?");
  }
  const VectorXd w = options.weights.size() ? options.weights : VectorXd::Ones(n);
  const VectorXd root = w.cwiseSqrt();
  const double alpha = options.alpha;

  // The weighted problem in X~ = W^1/2 X W^1/2: min ||X~ - G||_F with diag(X~) = w.
  MatrixXd shifted = S;
  if (alpha > 0.0) {
    shifted.diagonal().array() -= alpha;
    shifted /= 1.0 - alpha;
  }
  const MatrixXd G = root.asDiagonal() * shifted * root.asDiagonal();
  const VectorXd& b = w;

  Dual dual{G, b, {}, {}, 0.0, {}};
  VectorXd y = b - G.diagonal();
  if (!dual.evaluate(y, true)) throw std::runtime_error("nearest_correlation: the eigensolver did not converge");
  const double stop = options.tolerance * std::sqrt(static_cast<double>(n));
  constexpr double kArmijo = 1e-4;
  for (; out.iterations < options.max_iterations; ++out.iterations) {
    const double gradient = dual.F.norm();
    if (gradient <= stop) break;
    const Jacobian V(dual);
    const double mu = std::min(1e-2, gradient) * 1e-6;
    const VectorXd d = pcg(V, mu, -dual.F, std::min(1e-2, gradient), 200);
    // Armijo backtracking on theta (convex, so the Newton step is a descent direction).
    const double slope = dual.F.dot(d);
    const double theta0 = dual.theta;
    double t = 1.0;
    VectorXd trial = y + d;
    Dual probe{G, b, {}, {}, 0.0, {}};
    // Near the solution the decrease (about ||F||^2) falls below theta's own rounding: there the
    // comparison allows that rounding, or the full Newton step would be refused forever.
    const double rounding = 16.0 * std::numeric_limits<double>::epsilon() * (std::abs(theta0) + 1.0);
    // The full step, usually taken, is evaluated with eigenvectors so that the next iteration
    // reuses its eigendecomposition; shorter ones with eigenvalues only.
    for (int k = 0; k < 40; ++k) {
      if (!probe.evaluate(trial, k == 0)) throw std::runtime_error("nearest_correlation: the eigensolver did not converge");
      if (probe.theta <= theta0 + kArmijo * t * slope + rounding) break;
      t *= 0.5;
      trial = y + t * d;
    }
    y = trial;
    if (t == 1.0) {
      dual.P = std::move(probe.P);
      dual.lambda = std::move(probe.lambda);
      dual.theta = probe.theta;
      dual.F = std::move(probe.F);
    } else if (!dual.evaluate(y, true)) {
      throw std::runtime_error("nearest_correlation: the eigensolver did not converge");
    }
  }
  out.gradient_norm = dual.F.norm();
  out.converged = out.gradient_norm <= stop;
  if (!out.converged) {
    out.warnings.push_back("not converged within " + std::to_string(options.max_iterations) +
                           " iterations (||diag(X) - 1|| = " + detail::format_number(out.gradient_norm) +
                           "): the best iterate, rescaled to a unit diagonal");
  }

  // X~ = (G + diag y)_+, back to X, then the diagonal scaled to 1 (which keeps X semidefinite).
  const VectorXd positive = dual.lambda.cwiseMax(0.0);
  for (Index i = 0; i < n; ++i) out.clipped += dual.lambda(i) <= 0.0;
  MatrixXd X(n, n);
  X.triangularView<Eigen::Lower>() = dual.P * positive.asDiagonal() * dual.P.transpose();
  detail::make_symmetric_from_lower(X);
  const VectorXd unweight = root.cwiseInverse();
  X = unweight.asDiagonal() * X * unweight.asDiagonal();
  const VectorXd diagonal = X.diagonal().cwiseMax(std::numeric_limits<double>::min());
  const VectorXd scale = diagonal.cwiseSqrt().cwiseInverse();
  X = scale.asDiagonal() * X * scale.asDiagonal();
  if (alpha > 0.0) {
    X *= 1.0 - alpha;
    X.diagonal().array() += alpha;
  }
  X.diagonal().setOnes();
  detail::make_symmetric_from_lower(X);
  out.X = std::move(X);
  out.distance = (root.asDiagonal() * (out.X - S) * root.asDiagonal()).norm();
  out.cholesky_ok = Eigen::LLT<MatrixXd>(out.X).info() == Eigen::Success;
  return out;
}

}  // namespace spdfit
