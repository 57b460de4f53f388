#include "linalg.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Householder>
#include <Eigen/QR>
#include <Eigen/SVD>

namespace spdfit::detail {

namespace {
// Above this size divide and conquer is much faster than one-sided Jacobi and as accurate
// in the normwise sense the estimators need (Eigen's own switch-over is 16).
constexpr Index kJacobiMaxSize = 32;
}  // namespace

Svd svd(const Eigen::Ref<const MatrixXd>& A, bool compute_u, bool compute_v) {
  unsigned options = 0;
  if (compute_u) options |= Eigen::ComputeThinU;
  if (compute_v) options |= Eigen::ComputeThinV;
  Svd out;
  if (std::max(A.rows(), A.cols()) <= kJacobiMaxSize) {
    Eigen::JacobiSVD<MatrixXd> dec(A, options);
    out.s = dec.singularValues();
    if (compute_u) out.U = dec.matrixU();
    if (compute_v) out.V = dec.matrixV();
  } else {
    Eigen::BDCSVD<MatrixXd> dec(A, options);
    out.s = dec.singularValues();
    if (compute_u) out.U = dec.matrixU();
    if (compute_v) out.V = dec.matrixV();
  }
  return out;
}

VectorXd singular_values(const Eigen::Ref<const MatrixXd>& A) { return svd(A, false, false).s; }

Index numerical_rank(const Eigen::Ref<const VectorXd>& s, double cutoff) {
  if (s.size() == 0 || !(s(0) > 0.0)) return 0;
  const double threshold = cutoff * s(0);
  Index rank = 0;
  while (rank < s.size() && s(rank) > threshold) ++rank;
  return rank;
}

double condition_number(const Eigen::Ref<const VectorXd>& s) {
  if (s.size() == 0) return std::numeric_limits<double>::infinity();
  const double smin = s(s.size() - 1);
  if (!(smin > 0.0)) return std::numeric_limits<double>::infinity();
  return s(0) / smin;
}

MatrixXd triangular_factor(const Eigen::Ref<const MatrixXd>& A) {
  const Index cols = A.cols();
  MatrixXd R = MatrixXd::Zero(cols, cols);
  if (A.rows() == 0) return R;
  Eigen::HouseholderQR<MatrixXd> qr(A);
  const Index k = std::min(A.rows(), cols);
  R.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  return R;
}

void make_symmetric_from_lower(MatrixXd& X) {
  X.triangularView<Eigen::StrictlyUpper>() = X.transpose();
}

MatrixXd symmetric_part(const Eigen::Ref<const MatrixXd>& X) {
  // Halving first keeps entries near the double range finite; addition commutes, so the
  // result is exactly symmetric.
  return 0.5 * X + 0.5 * X.transpose();
}

std::optional<int> scale_exponent(const Eigen::Ref<const MatrixXd>& X) {
  if (X.size() == 0) return std::nullopt;
  const double biggest = X.cwiseAbs().maxCoeff();
  if (!(biggest > 0.0)) return std::nullopt;
  int e = 0;
  std::frexp(biggest, &e);  // biggest = f 2^e with f in [0.5, 1): |x| < 2^e
  return e;
}

MatrixXd times_power_of_two(const Eigen::Ref<const MatrixXd>& X, int e) {
  // 2^e is itself a normal double for |e| <= 1022; beyond that (denormal data, say) scale each
  // entry with ldexp so the factor never overflows or underflows on its own.
  if (e >= -1022 && e <= 1022) return X * std::ldexp(1.0, e);
  return X.unaryExpr([e](double x) { return std::ldexp(x, e); });
}

}  // namespace spdfit::detail
