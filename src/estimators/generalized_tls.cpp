#include "estimators/generalized_tls.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "estimators/kernels.hpp"
#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {
// Eigenvalues of Sigma_A within this many n eps of its largest are zero: exact directions.
constexpr double kExactMargin = 64.0;
}  // namespace

void generalized_tls(const DynamicReduction& data, const ScaledNoise& noise, GeneralizedTls& out) {
  const Index n = data.n, d = data.d;
  out = GeneralizedTls{};
  if (noise.a_zero) {
    // No noise in A: least squares is the maximum-likelihood estimate of an unconstrained X,
    // whatever Sigma_B (each column of B on its own, with the same A).
    least_squares_kernel(data, out.X_s);
    out.least_squares = true;
    out.exact_directions = n;
    out.exists = out.unique = true;
    return;
  }

  // T_A: Sigma_A's exact directions first, then the noisy ones scaled to unit variance.
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig_a(noise.cov_a);
  const VectorXd& s = eig_a.eigenvalues();  // ascending
  const double margin =
      kExactMargin * static_cast<double>(n) * std::numeric_limits<double>::epsilon() * std::abs(s(n - 1));
  Index n1 = 0;
  while (n1 < n && s(n1) <= margin) ++n1;
  const Index n2 = n - n1;
  MatrixXd T_a = eig_a.eigenvectors();
  for (Index j = n1; j < n; ++j) T_a.col(j) /= std::sqrt(s(j));
  // T_B = Sigma_B^-1/2 and its inverse.
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig_b(noise.cov_b);
  const VectorXd root_b = eig_b.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const MatrixXd& V_b = eig_b.eigenvectors();
  const MatrixXd T_b = V_b * root_b.cwiseInverse().asDiagonal() * V_b.transpose();
  const MatrixXd T_b_inv = V_b * root_b.asDiagonal() * V_b.transpose();

  // The factor of [A T_A, B T_B], in one common power-of-two scale (TLS is invariant only under a
  // common scaling).
  MatrixXd Rw = MatrixXd::Zero(n + d, n + d);
  Rw.topLeftCorner(n, n).noalias() = data.R11 * T_a;
  Rw.topRightCorner(n, d).noalias() = data.R12 * T_b;
  Rw.bottomRightCorner(d, d).noalias() = data.R22 * T_b;
  const int e = scale_exponent(Rw).value_or(0);
  multiply_by_power_of_two(Rw, -e);
  MatrixXd R;
  triangular_factor_into<MatrixXd>(Rw, R);

  // TLS on the part orthogonal to the exact columns: [R22 R2b; 0 Rbb], n2 + d columns.
  const MatrixXd part = R.bottomRightCorner(n2 + d, n2 + d);
  BasicSvd<MatrixXd> dec;
  svd_into(part, dec, false, true);
  out.exact_directions = n1;
  out.sigma_n = std::ldexp(dec.s(n2 - 1), e);
  out.sigma_n1 = std::ldexp(dec.s(n2), e);
  out.correction = std::ldexp(dec.s.tail(d).norm(), e);
  const MatrixXd V12 = dec.V.topRightCorner(n2, d);
  const MatrixXd V22 = dec.V.bottomRightCorner(d, d);
  out.v22_min = singular_values(V22)(d - 1);
  const double cutoff = data.options.rank_cutoff(data.m, n + d);
  out.exists = out.v22_min > cutoff;
  if (!out.exists) return;
  out.unique = dec.s(n2 - 1) - dec.s(n2) > cutoff * dec.s(0);
  MatrixXd Xw(n, d);
  Xw.bottomRows(n2) = -V22.transpose().partialPivLu().solve(V12.transpose()).transpose();
  if (n1 > 0) {
    // The exact columns by least squares given the others: R11 X1 = R1b - R12 X2.
    Xw.topRows(n1) = R.topRightCorner(n1, d) - R.block(0, n1, n1, n2) * Xw.bottomRows(n2);
    R.topLeftCorner(n1, n1).triangularView<Eigen::Upper>().solveInPlace(Xw.topRows(n1));
  }
  // A T_A Xw = B T_B, so X = T_A Xw T_B^-1 (in the factor's units: T_A, T_B were built there).
  out.X_s = T_a * Xw * T_b_inv;
}

}  // namespace spdfit::detail
