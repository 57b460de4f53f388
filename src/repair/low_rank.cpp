#include "repair/low_rank.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <random>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Birgin, Martinez & Raydan's constants: the Armijo fraction, the memory of the non-monotone
// search, and the safeguards of the spectral step.
constexpr double kArmijo = 1e-4;
constexpr int kMemory = 10;
constexpr double kStepMin = 1e-12, kStepMax = 1e12;

// Whether C is exactly symmetric, compared a block at a time (cache-friendly for large n).
bool exactly_symmetric(const Eigen::Ref<const MatrixXd>& C) {
  const Index n = C.rows();
  constexpr Index kBlock = 64;
  for (Index j0 = 0; j0 < n; j0 += kBlock) {
    for (Index i0 = j0; i0 < n; i0 += kBlock) {
      const Index rows = std::min(kBlock, n - i0), cols = std::min(kBlock, n - j0);
      if (C.block(i0, j0, rows, cols) != C.block(j0, i0, cols, rows).transpose()) return false;
    }
  }
  return true;
}

}  // namespace

LowRankProblem::LowRankProblem(const Eigen::Ref<const MatrixXd>& C, VectorXd w, bool sphere)
    : C_(C), w_(std::move(w)), sphere_(sphere) {
  const Index n = C.rows();
  if (w_.size() == 0) w_ = VectorXd::Ones(n);
  symmetric_ = exactly_symmetric(C);
  // sum_ij w_i w_j s_ij^2 a column at a time.
  double sum = 0.0;
  for (Index j = 0; j < n; ++j) {
    double column = 0.0;
    for (Index i = 0; i < n; ++i) {
      const double s = symmetric_ ? C(i, j) : 0.5 * C(i, j) + 0.5 * C(j, i);
      column += w_(i) * s * s;
    }
    sum += w_(j) * column;
  }
  c2_ = sum;
  scale_ = 4.0 * std::sqrt(w_.maxCoeff()) * std::max(std::sqrt(c2_), 1e-300);
}

void LowRankProblem::product(const MatrixXd& V, MatrixXd& out) const {
  multiply(C_, false, V, false, out);
  if (!symmetric_) {
    MatrixXd transposed;
    multiply(C_, true, V, false, transposed);
    out = 0.5 * out + 0.5 * transposed;
  }
}

double LowRankProblem::evaluate(const MatrixXd& Y, MatrixXd* gradient) const {
  const MatrixXd DY = w_.asDiagonal() * Y;
  MatrixXd Z;
  product(DY, Z);                            // S D Y
  const MatrixXd A = Y.transpose() * DY;     // Y^T D Y, K x K
  const VectorXd norms = Y.rowwise().squaredNorm();
  const VectorXd s = C_.diagonal();
  // sum_{i != j} = sum_{ij} - sum_i: ||A||^2 - 2 tr(Y^T D Z) + c2 - sum_i w_i^2 (||y_i||^2 - s_ii)^2.
  const VectorXd diagonal = w_.cwiseProduct(norms - s);
  const double f = A.squaredNorm() - 2.0 * DY.cwiseProduct(Z).sum() + c2_ - diagonal.squaredNorm();
  if (gradient) {
    // 4 D (Y A - Z) - 4 D diag(w o (||y_i||^2 - s_ii)) Y.
    *gradient = Y * A - Z;
    for (Index i = 0; i < Y.rows(); ++i) gradient->row(i) -= diagonal(i) * Y.row(i);
    *gradient = 4.0 * (w_.asDiagonal() * *gradient);
  }
  return f;  // may be a little below 0 from rounding near an exact fit
}

void LowRankProblem::project(MatrixXd& Y) const {
  for (Index i = 0; i < Y.rows(); ++i) {
    const double norm = Y.row(i).norm();
    if (sphere_) {
      if (norm > 0.0) {
        Y.row(i) /= norm;
      } else {
        Y.row(i).setZero();
        Y(i, 0) = 1.0;
      }
    } else if (norm > 1.0) {
      Y.row(i) /= norm;
    }
  }
}

double LowRankProblem::rounding() const { return 64.0 * std::numeric_limits<double>::epsilon() * c2_; }

double LowRankProblem::residual(const MatrixXd& Y, const MatrixXd& gradient) const {
  MatrixXd r;
  if (sphere_) {
    r = gradient;
    for (Index i = 0; i < Y.rows(); ++i) r.row(i) -= gradient.row(i).dot(Y.row(i)) * Y.row(i);
  } else {
    r = Y - gradient;
    project(r);
    r -= Y;
  }
  const double a = (Y.transpose() * w_.asDiagonal() * Y).norm();
  return r.norm() / (scale_ + 4.0 * std::sqrt(w_.maxCoeff()) * a);
}

double LowRankProblem::distance(const MatrixXd& Y) const {
  const Index n = Y.rows();
  const MatrixXd Yt = Y.transpose();
  double sum = 0.0;
  VectorXd column(n);
  for (Index j = 0; j < n; ++j) {
    column.noalias() = Y * Yt.col(j);
    column(j) = 1.0;  // X's diagonal: 1 - ||y_j||^2 + ||y_j||^2
    if (symmetric_) {
      column -= C_.col(j);
    } else {
      column -= 0.5 * C_.col(j) + 0.5 * C_.row(j).transpose();
    }
    sum += w_(j) * column.cwiseAbs2().dot(w_);
  }
  double asymmetric = 0.0;
  if (!symmetric_) {
    for (Index j = 0; j < n; ++j) {
      for (Index i = 0; i < n; ++i) asymmetric += w_(i) * w_(j) * std::pow(0.5 * (C_(i, j) - C_(j, i)), 2);
    }
  }
  return std::sqrt(sum + asymmetric);
}

LowRankResult spectral_projected_gradient(const LowRankProblem& problem, MatrixXd Y, int max_iterations,
                                          double tolerance) {
  LowRankResult out;
  problem.project(Y);
  MatrixXd g;
  double f = problem.evaluate(Y, &g);
  std::deque<double> history{f};
  // The tangent (sphere) or projected (ball) direction for step length lambda.
  const auto direction = [&problem](const MatrixXd& Yc, const MatrixXd& gc, double lambda) {
    MatrixXd d;
    if (problem.sphere()) {
      d = gc;
      for (Index i = 0; i < Yc.rows(); ++i) d.row(i) -= gc.row(i).dot(Yc.row(i)) * Yc.row(i);
      d *= -lambda;
    } else {
      d = Yc - lambda * gc;
      problem.project(d);
      d -= Yc;
    }
    return d;
  };
  out.residual = problem.residual(Y, g);
  double lambda = 1.0 / std::max(g.cwiseAbs().maxCoeff(), 1e-300);
  MatrixXd trial, g_trial;
  for (; out.iterations < max_iterations && out.residual > tolerance; ++out.iterations) {
    const MatrixXd d = direction(Y, g, lambda);
    // On the sphere d is tangent, and g . d = (tangent part of g) . d = -lambda ||grad_R||^2: computed
    // from the tangent part, as g's radial part (large, and irrelevant) would bury it in rounding.
    double slope = g.cwiseProduct(d).sum();
    if (problem.sphere()) slope = -d.squaredNorm() / lambda;
    if (!(slope < 0.0)) break;  // no descent left at this precision
    // Near a minimizer the decrease (about the squared gradient) falls below the rounding of f,
    // which is computed as a difference of terms of order ||W^1/2 C W^1/2||^2: the comparison
    // allows that rounding, or the search would stop short of the stopping test.
    const double reference = *std::max_element(history.begin(), history.end()) + problem.rounding();
    double alpha = 1.0, f_trial = 0.0;
    bool accepted = false;
    for (int k = 0; k < 50; ++k) {
      trial = Y + alpha * d;
      if (problem.sphere()) problem.project(trial);
      f_trial = problem.evaluate(trial, &g_trial);
      if (f_trial <= reference + kArmijo * alpha * slope) {
        accepted = true;
        break;
      }
      // A safeguarded quadratic interpolation of f along the step.
      const double denominator = 2.0 * (f_trial - f - alpha * slope);
      double next = denominator > 0.0 ? -slope * alpha * alpha / denominator : 0.5 * alpha;
      alpha = std::clamp(next, 0.1 * alpha, 0.5 * alpha);
    }
    if (!accepted) break;
    // The spectral (Barzilai-Borwein) step from the change in Y and in the (tangent) gradient.
    const MatrixXd s = trial - Y;
    MatrixXd y = g_trial - g;
    if (problem.sphere()) {
      for (Index i = 0; i < y.rows(); ++i) y.row(i) -= y.row(i).dot(trial.row(i)) * trial.row(i);
    }
    const double sy = s.cwiseProduct(y).sum();
    lambda = sy > 0.0 ? std::clamp(s.squaredNorm() / sy, kStepMin, kStepMax) : kStepMax;
    Y.swap(trial);
    g.swap(g_trial);
    f = f_trial;
    history.push_back(f);
    if (static_cast<int>(history.size()) > kMemory) history.pop_front();
    out.residual = problem.residual(Y, g);
  }
  out.converged = out.residual <= tolerance;
  out.objective = f;
  out.Y = std::move(Y);
  return out;
}

void leading_eigenvectors(const Eigen::Ref<const MatrixXd>& C, Index K, MatrixXd& vectors, VectorXd& values) {
  const Index n = C.rows();
  // Oversampled block power iteration (Halko, Martinsson & Tropp 2011, algorithm 4.4): a few
  // sweeps give the leading invariant subspace well enough for a start.
  const Index block = std::min(n, K + std::max<Index>(5, K));
  constexpr int kSweeps = 6;
  std::mt19937_64 generator(20240611);
  std::normal_distribution<double> normal;
  MatrixXd V(n, block);
  for (Index j = 0; j < block; ++j)
    for (Index i = 0; i < n; ++i) V(i, j) = normal(generator);
  const bool symmetric = exactly_symmetric(C);
  MatrixXd W, T;
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    Eigen::HouseholderQR<MatrixXd> qr(V);
    V = qr.householderQ() * MatrixXd::Identity(n, block);
    multiply(C, false, V, false, W);
    if (!symmetric) {
      multiply(C, true, V, false, T);
      W = 0.5 * W + 0.5 * T;
    }
    V.swap(W);
  }
  Eigen::HouseholderQR<MatrixXd> qr(V);
  V = qr.householderQ() * MatrixXd::Identity(n, block);
  multiply(C, false, V, false, W);
  if (!symmetric) {
    multiply(C, true, V, false, T);
    W = 0.5 * W + 0.5 * T;
  }
  MatrixXd small = V.transpose() * W;
  small = 0.5 * (small + small.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(small);
  // Descending: the K largest.
  vectors.resize(n, K);
  values.resize(K);
  for (Index k = 0; k < K; ++k) {
    values(k) = eig.eigenvalues()(block - 1 - k);
    vectors.col(k) = V * eig.eigenvectors().col(block - 1 - k);
  }
}

}  // namespace spdfit::detail
