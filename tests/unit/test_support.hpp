// Generators with known answers and comparison helpers shared by the unit tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>

namespace spdfit::test {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

inline constexpr double kEps = std::numeric_limits<double>::epsilon();

/// A reproducible source of random matrices.
class Generator {
 public:
  explicit Generator(unsigned seed) : engine_(seed) {}

  double normal() { return normal_(engine_); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }

  MatrixXd gaussian(Index rows, Index cols) {
    MatrixXd M(rows, cols);
    for (Index j = 0; j < cols; ++j)
      for (Index i = 0; i < rows; ++i) M(i, j) = normal();
    return M;
  }

  /// A random rows x cols matrix with orthonormal columns (Haar, via QR with sign fix).
  MatrixXd orthonormal(Index rows, Index cols) {
    Eigen::HouseholderQR<MatrixXd> qr(gaussian(rows, cols));
    MatrixXd Q = qr.householderQ() * MatrixXd::Identity(rows, cols);
    for (Index j = 0; j < cols; ++j)
      if (qr.matrixQR()(j, j) < 0) Q.col(j) *= -1.0;
    return Q;
  }

  /// An m x n matrix with the given singular values (length n).
  MatrixXd with_singular_values(Index m, const VectorXd& s) {
    const Index n = s.size();
    return orthonormal(m, n) * s.asDiagonal() * orthonormal(n, n).transpose();
  }

  /// An m x n matrix with condition number `cond` (singular values log-spaced from 1 to 1/cond).
  MatrixXd with_condition(Index m, Index n, double cond) {
    return with_singular_values(m, log_spaced(n, cond));
  }

  /// A symmetric positive definite matrix with eigenvalues log-spaced from 1 to cond, exactly symmetric.
  MatrixXd spd(Index n, double cond = 10.0) {
    const MatrixXd W = orthonormal(n, n);
    MatrixXd X = W * log_spaced(n, 1.0 / cond).asDiagonal() * W.transpose();
    return symmetrize(X);
  }

  /// Values log-spaced from 1 down to 1/cond (n of them).
  static VectorXd log_spaced(Index n, double cond) {
    VectorXd s(n);
    for (Index i = 0; i < n; ++i) s(i) = n == 1 ? 1.0 : std::pow(cond, -static_cast<double>(i) / (n - 1));
    return s;
  }

  static MatrixXd symmetrize(const MatrixXd& X) { return 0.5 * (X + X.transpose()); }

 private:
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_;
};

/// ||X - Y||_F / ||Y||_F (or ||X||_F when Y is zero).
inline double relative_error(const MatrixXd& X, const MatrixXd& Y) {
  const double denominator = Y.norm() > 0 ? Y.norm() : 1.0;
  return (X - Y).norm() / denominator;
}

}  // namespace spdfit::test

namespace spdfit {
// The tests live in namespace spdfit and use these names unqualified.
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
}  // namespace spdfit
