#include "repair/pattern_newton.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The margin of the stopping test over the rounding level of the dual gradient (as
// correlation_newton's: the eigendecomposition makes F exact only for a matrix within
// about eps ||M||_2 of M).
constexpr double kGradientRounding = 2.0;
// Above this share of the n^2 entries fixed, the Jacobian's sparse products are done densely
// (BLAS on an n x n matrix), which is then faster than the entry-by-entry loops.
constexpr double kDenseShare = 1.0 / 16.0;
// How far the most negative eigenvalue of G + A^* y must exceed the largest positive one, after the
// iterations ran out, to call the multipliers divergent (converged problems measured: below 1).
constexpr double kDivergence = 10.0;
// The conjugate gradients of one Newton step (pcg): after kCgExpensive iterations (about an
// eigendecomposition's cost at r = n / 10) they stop at a relative residual of kLooseForcing, and
// they stop at kCgMaxIterations.
constexpr double kLooseForcing = 0.1;
constexpr int kCgExpensive = 20;
constexpr int kCgMaxIterations = 200;

Index positive_count(const VectorXd& lambda) {
  const Index n = lambda.size();
  Index r = 0;
  while (r < n && lambda(n - 1 - r) > 0.0) ++r;
  return r;
}

// <E_p, E_p>-style weights: A(X)_p = 2 X_ij off the diagonal, X_ii on it.
double scale_of(const FixedPattern& pattern, Index p) { return pattern.row[p] == pattern.col[p] ? 1.0 : 2.0; }

// The generalized Jacobian of the dual gradient at M = P diag(lambda) P^T, restricted to the
// pattern: V h = A(P (Omega o (P^T A^*(h) P)) P^T), Omega as in Qi & Sun (2006, eq. (20)). With the
// r positive eigenvectors P1 last, K = P1^T H P = [K2 K1] and J = (U + W) P1^T + P1 W^T for
// U = P1 K1, W = P2 (Omega12 o K2)^T: products of n x n by n x r matrices, then O(r) per entry.
class PatternJacobian {
 public:
  PatternJacobian(const MatrixXd& P, const VectorXd& lambda, const FixedPattern& pattern)
      : P_(P), pattern_(pattern), r_(positive_count(lambda)) {
    const Index n = lambda.size(), r = r_, a = n - r;
    dense_ = static_cast<double>(pattern.size()) > kDenseShare * static_cast<double>(n) * static_cast<double>(n);
    omega_.resize(a, r);  // Omega12^T: (j, i) for the non-positive j and positive i
    for (Index i = 0; i < r; ++i) {
      const double li = lambda(a + i);
      for (Index j = 0; j < a; ++j) omega_(j, i) = li / (li - lambda(j));
    }
    P1t_ = P.rightCols(r).transpose();
    // The Jacobian's products in single precision: an inexact Newton method needs its directions
    // only to the forcing term (1e-2 and less, but 0.1 where the conjugate gradients are
    // expensive, as they are for ill-conditioned Jacobians), and sgemm takes
    // about half dgemm's time (n = 1000 --fixed benchmark: 17.2 s of one core in double, 10.8 s in
    // single, the same Newton steps). The gradient and the stopping test stay in double.
    Pf_ = P.cast<float>();
    omegaf_ = omega_.cast<float>();
    // The diagonal of V (the preconditioner): <E_p, J[E_p]> = T_ij (diagonal) or 2 T_ij + 2 m^T Omega m
    // (off it), T = Q Omega Q^T for Q = P o P, m = P_i. o P_j.; of m^T Omega m the Omega11 block
    // (P1_i . P1_j)^2 is kept (the rest, of either sign, is small where the preconditioner matters).
    const Index m = pattern.size();
    diagonal_.resize(m);
    if (r == 0) {
      diagonal_.setConstant(1.0);
      return;
    }
    const MatrixXd Q1 = P.rightCols(r).cwiseAbs2();
    const VectorXd s = Q1.rowwise().sum();
    MatrixXd Mq;  // Q1 Omega12: n x a
    MatrixXd Q2;
    if (a > 0) {
      Q2 = P.leftCols(a).cwiseAbs2();
      multiply(Q1, false, omega_, true, Mq);
    }
    const MatrixXd Mqt = a > 0 ? MatrixXd(Mq.transpose()) : MatrixXd();
    const MatrixXd Q2t = a > 0 ? MatrixXd(Q2.transpose()) : MatrixXd();
    for (Index p = 0; p < m; ++p) {
      const Index i = pattern.row[p], j = pattern.col[p];
      double t = s(i) * s(j);
      if (a > 0) t += Mqt.col(i).dot(Q2t.col(j)) + Mqt.col(j).dot(Q2t.col(i));
      if (i != j) {
        const double c = P1t_.col(i).dot(P1t_.col(j));
        t = 2.0 * (t + c * c);
      }
      diagonal_(p) = std::max(t, 1e-12);
    }
  }

  void apply(const VectorXd& h, VectorXd& out) {
    const Index n = P_.rows(), r = r_, a = n - r, m = pattern_.size();
    out.setZero(m);
    if (r == 0) return;
    const auto P1 = P_.rightCols(r);
    // H P1 for H = A^*(h).
    if (dense_) {
      H_.setZero(n, n);
      for (Index p = 0; p < m; ++p) {
        const Index i = pattern_.row[p], j = pattern_.col[p];
        H_(i, j) += h(p);
        if (i != j) H_(j, i) += h(p);
      }
      multiply(H_, false, P1, false, HP1_);
    } else {
      HP1t_.setZero(r, n);
      for (Index p = 0; p < m; ++p) {
        const Index i = pattern_.row[p], j = pattern_.col[p];
        HP1t_.col(i) += h(p) * P1t_.col(j);
        if (i != j) HP1t_.col(j) += h(p) * P1t_.col(i);
      }
      HP1_ = HP1t_.transpose();
    }
    // The three products of n x n by n x r matrices in single precision (see the constructor), on
    // H P1 scaled to a largest entry of 1 (the map is linear) so that no float underflows.
    const double size = HP1_.cwiseAbs().maxCoeff();
    if (!(size > 0.0)) return;
    HP1f_ = (HP1_ / size).cast<float>();
    multiply(Pf_, true, HP1f_, false, Ktf_);  // (P1^T H P)^T: n x r
    multiply(Pf_.rightCols(r), false, Ktf_.bottomRows(r), false, Uf_);  // P1 K1 (K1 symmetric)
    if (a > 0) {
      Lf_ = omegaf_.cwiseProduct(Ktf_.topRows(a));
      multiply(Pf_.leftCols(a), false, Lf_, false, Wf_);
      Uf_ += Wf_;  // V = U + W
      W_ = size * Wf_.cast<double>();
    } else {
      W_.setZero(n, r);
    }
    U_ = size * Uf_.cast<double>();
    if (dense_) {
      multiply(U_, false, P1, true, J_);
      multiply(P1, false, W_, true, H_);
      for (Index p = 0; p < m; ++p) {
        const Index i = pattern_.row[p], j = pattern_.col[p];
        const double value = J_(i, j) + H_(i, j);
        out(p) = i == j ? value : 2.0 * value;
      }
      return;
    }
    const MatrixXd Vt = U_.transpose(), Wt = W_.transpose();
    for (Index p = 0; p < m; ++p) {
      const Index i = pattern_.row[p], j = pattern_.col[p];
      const double value = Vt.col(i).dot(P1t_.col(j)) + P1t_.col(i).dot(Wt.col(j));
      out(p) = i == j ? value : 2.0 * value;
    }
  }

  const VectorXd& diagonal() const { return diagonal_; }

 private:
  const MatrixXd& P_;
  const FixedPattern& pattern_;
  Index r_;
  bool dense_ = false;
  MatrixXd omega_, P1t_;
  VectorXd diagonal_;
  Eigen::MatrixXf Pf_, omegaf_;
  MatrixXd H_, HP1_, HP1t_, U_, W_, J_;  // buffers of apply
  Eigen::MatrixXf HP1f_, Ktf_, Lf_, Uf_, Wf_;
};

// A limited-memory BFGS approximation of the inverse of the previous Newton step's Jacobian, built
// from pairs (p, (V + mu I) p) of its conjugate-gradient run over the diagonal preconditioner: the
// preconditioner of the next run. Near the solution the Jacobian changes little from step to step,
// and its small eigenvalues (a kept block with small eigenvalues makes many) are what the diagonal
// misses: on the n = 1000 benchmark of docs/performance.md the conjugate-gradient iterations fell
// from 2140 to 1280.
class RecycledPreconditioner {
 public:
  // Sets the diagonal part for this run (the pairs are the previous run's).
  void start(const VectorXd& inverse_diagonal) {
    inverse_diagonal_ = inverse_diagonal;
    if (!s_.empty() && s_.front().size() != inverse_diagonal.size()) clear();
    alpha_.resize(s_.size());
    next_s_.clear();
    next_y_.clear();
    next_rho_.clear();
  }

  // z = H r by the two-loop recursion.
  void apply(const VectorXd& r, VectorXd& z) {
    q_ = r;
    for (std::size_t k = s_.size(); k-- > 0;) {
      alpha_[k] = rho_[k] * s_[k].dot(q_);
      q_ -= alpha_[k] * y_[k];
    }
    z = inverse_diagonal_.cwiseProduct(q_);
    for (std::size_t k = 0; k < s_.size(); ++k) z += (alpha_[k] - rho_[k] * y_[k].dot(z)) * s_[k];
  }

  void record(const VectorXd& p, const VectorXd& w, double pw) {
    next_s_.push_back(p);
    next_y_.push_back(w);
    next_rho_.push_back(1.0 / pw);
  }

  // After a run: its pairs, at most kPairs spread evenly over it, replace the previous run's.
  void finish() {
    const std::size_t total = next_s_.size(), keep = std::min(total, kPairs);
    clear();
    for (std::size_t k = 0; k < keep; ++k) {
      const std::size_t i = keep == total ? k : k * total / keep;
      s_.push_back(std::move(next_s_[i]));
      y_.push_back(std::move(next_y_[i]));
      rho_.push_back(next_rho_[i]);
    }
  }

 private:
  // Two-loop cost 4 kPairs m per application against the Jacobian's products of n x n by n x r
  // matrices; 50 measured faster than 20 or 200.
  static constexpr std::size_t kPairs = 50;
  void clear() {
    s_.clear();
    y_.clear();
    rho_.clear();
  }
  VectorXd inverse_diagonal_, q_;
  std::vector<VectorXd> s_, y_, next_s_, next_y_;
  std::vector<double> rho_, next_rho_, alpha_;
};

// Preconditioned conjugate gradients for (V + mu I) d = rhs, to a relative residual `tol`, or
// kLooseForcing once kCgExpensive iterations are spent.
VectorXd pcg(PatternJacobian& V, double mu, const VectorXd& rhs, double tol, int max_iterations,
             RecycledPreconditioner& preconditioner) {
  const Index m = rhs.size();
  VectorXd d = VectorXd::Zero(m);
  VectorXd r = rhs;
  preconditioner.start((V.diagonal().array() + mu).max(1e-12).inverse().matrix());
  VectorXd z;
  preconditioner.apply(r, z);
  VectorXd p = z, w;
  double rz = r.dot(z);
  const double stop = tol * rhs.norm();
  const double loose_stop = kLooseForcing * rhs.norm();
  for (int iterations = 0; iterations < max_iterations && r.norm() > stop; ++iterations) {
    if (iterations >= kCgExpensive && r.norm() <= loose_stop) break;
    V.apply(p, w);
    w += mu * p;
    const double pw = p.dot(w);
    if (!(pw > 0.0)) break;
    preconditioner.record(p, w, pw);
    const double step = rz / pw;
    d += step * p;
    r -= step * w;
    preconditioner.apply(r, z);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  preconditioner.finish();
  return d;
}

// P := G + A^*(y), then its eigendecomposition in place.
void decompose(const MatrixXd& G, const FixedPattern& pattern, const VectorXd& y, MatrixXd& P, VectorXd& lambda,
               bool vectors) {
  P = G;
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    P(i, j) += y(p);
    if (i != j) P(j, i) += y(p);
  }
  if (!symmetric_eigen_in_place(P, lambda, vectors)) throw std::runtime_error("the eigensolver did not converge");
}

double theta_at(const VectorXd& lambda, const VectorXd& b, const VectorXd& y) {
  return 0.5 * lambda.cwiseMax(0.0).squaredNorm() - b.dot(y);
}

// A((G + A^* y)_+) - b from the eigendecomposition: X_ij = Q_i . Q_j for Q = P1 diag(lambda_+)^1/2.
VectorXd gradient_at(const MatrixXd& P, const VectorXd& lambda, const FixedPattern& pattern, const VectorXd& b) {
  const Index n = lambda.size(), r = positive_count(lambda);
  MatrixXd Qt = P.rightCols(r).transpose();
  for (Index k = 0; k < r; ++k) Qt.row(k) *= std::sqrt(lambda(n - r + k));
  VectorXd F(pattern.size());
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    F(p) = scale_of(pattern, p) * Qt.col(i).dot(Qt.col(j)) - b(p);
  }
  return F;
}

// The gradient in entry units (X_ij - B_ij), for the stopping test.
double entry_norm(const VectorXd& F, const FixedPattern& pattern) {
  double sum = 0.0;
  for (Index p = 0; p < pattern.size(); ++p) {
    const double e = F(p) / scale_of(pattern, p);
    sum += e * e;
  }
  return std::sqrt(sum);
}

}  // namespace

PatternNewtonResult pattern_newton(MatrixXd G, const FixedPattern& pattern, const MatrixXd& B, int max_iterations,
                                   double tolerance, double infeasible_above, MatrixXd* multiplier) {
  const Index n = G.rows(), m = pattern.size();
  PatternNewtonResult out;
  VectorXd b(m), y(m);
  for (Index p = 0; p < m; ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    b(p) = scale_of(pattern, p) * B(i, j);
    y(p) = B(i, j) - G(i, j);  // G + A^* y then has the targets
  }
  const double half_g = 0.5 * G.squaredNorm();
  MatrixXd P(n, n);
  VectorXd lambda;
  decompose(G, pattern, y, P, lambda, true);
  double theta = theta_at(lambda, b, y);
  VectorXd F = gradient_at(P, lambda, pattern, b);
  const double root_m = std::sqrt(static_cast<double>(std::max<Index>(m, 1)));
  auto stop = [&]() {
    const double norm_m = std::max(std::abs(lambda(0)), std::abs(lambda(n - 1)));
    return std::max(tolerance, kGradientRounding * root_m * kEps * norm_m);
  };
  constexpr double kArmijo = 1e-4;
  RecycledPreconditioner recycled;
  const double initial_rms = std::max(F.norm() / root_m, std::numeric_limits<double>::min());
  for (; out.iterations < max_iterations; ++out.iterations) {
    if (half_g - theta > infeasible_above) {
      out.infeasible = true;
      break;
    }
    const double gradient = F.norm();
    if (entry_norm(F, pattern) <= stop()) break;
    VectorXd step;
    {
      PatternJacobian V(P, lambda, pattern);
      const double mu = std::min(1e-2, gradient) * 1e-6;
      // The inexact Newton method's forcing term: correlation_newton's (1e-2, less as the gradient
      // falls, and no tighter than the stopping test needs), relaxed to 0.1 by pcg once a solve is
      // expensive. A kept block with small eigenvalues makes the Jacobian ill conditioned
      // (condition numbers of 10^4 measured, with a cluster of small eigenvalues the diagonal
      // preconditioner leaves as they are); then one more Newton step is cheaper than the hundreds
      // of iterations a tighter solve takes (n = 1000 benchmark: 33 s of CPU against 19 s), while
      // well-conditioned problems keep their few quadratically convergent steps.
      const double forcing = std::min(1e-2, gradient / initial_rms);
      step = pcg(V, mu, -F, std::min(std::max(forcing, 0.5 * stop() / gradient), 0.5), kCgMaxIterations, recycled);
    }
    const double slope = F.dot(step);
    const double theta0 = theta;
    const double rounding = 16.0 * kEps * (std::abs(theta0) + 1.0);
    double t = 1.0;
    VectorXd trial = y + step;
    for (int k = 0; k < 40; ++k) {
      decompose(G, pattern, trial, P, lambda, k == 0);
      theta = theta_at(lambda, b, trial);
      if (theta <= theta0 + kArmijo * t * slope + rounding) break;
      t *= 0.5;
      trial = y + t * step;
    }
    y = std::move(trial);
    if (t != 1.0) {
      decompose(G, pattern, y, P, lambda, true);
      theta = theta_at(lambda, b, y);
    }
    F = gradient_at(P, lambda, pattern, b);
  }
  out.residual = entry_norm(F, pattern);
  out.converged = !out.infeasible && out.residual <= stop();
  out.dual_value = half_g - theta;
  if (half_g - theta > infeasible_above) out.infeasible = true;

  G = MatrixXd();
  const Index r = positive_count(lambda);
  // Not converged with the multipliers grown far past the data (G's eigenvalues, in these units, are
  // of the order of its largest positive ones): y diverges while theta converges, the signature of a
  // dual with no minimizer, which is what kept entries admitting only singular completions give (the
  // iterate's most negative eigenvector spans a direction that every admissible X must annihilate).
  if (!out.converged && !out.infeasible && r > 0 && r < n && -lambda(0) > kDivergence * lambda(n - 1)) {
    const VectorXd v = P.col(0).cwiseAbs();
    const double largest = v.maxCoeff();
    for (Index i = 0; i < n; ++i) {
      if (v(i) >= 0.5 * largest) out.singular_rows.push_back(i);
    }
  }
  out.clipped = n - r;
  if (multiplier) {
    // Z = -(G + A^* y)_- = P2 diag(-lambda_-) P2^T, before P's positive columns are scaled.
    MatrixXd Q = P.leftCols(n - r);
    for (Index k = 0; k < n - r; ++k) Q.col(k) *= std::sqrt(-lambda(k));
    lower_gram(Q, *multiplier);
    make_symmetric_from_lower(*multiplier);
  }
  for (Index j = n - r; j < n; ++j) P.col(j) *= std::sqrt(lambda(j));
  lower_gram(P.rightCols(r), out.X);
  make_symmetric_from_lower(out.X);
  for (Index p = 0; p < m; ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    out.X(i, j) = out.X(j, i) = B(i, j);
  }
  return out;
}

}  // namespace spdfit::detail
