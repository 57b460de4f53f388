#include "spdfit/nearest_spd.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kernels.hpp"
#include "linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
Index nearest_spd_kernel(const SquareMatrix<MaxN>& x, double floor, SquareMatrix<MaxN>& y, double& min_before) {
  using Matrix = SquareMatrix<MaxN>;
  // Higham 1988: the nearest symmetric matrix is S = (X + X^T)/2, and the nearest one with
  // eigenvalues >= min_eig clips the eigenvalues of S = W diag(lambda) W^T. For min_eig = 0 this
  // is (S + H)/2 with H the symmetric polar factor of S (thesis eq. 4.39).
  const Matrix S = symmetric_part(x);
  Eigen::SelfAdjointEigenSolver<Matrix> eig(S);
  if (eig.info() != Eigen::Success) return -1;
  typename BasicReduction<MaxN>::Vector lambda = eig.eigenvalues();
  min_before = lambda(0);
  Index clipped = 0;
  for (Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) < floor) {
      lambda(i) = floor;
      ++clipped;
    }
  }
  if (clipped == 0) {
    y = S;  // already admissible: no rounding from re-assembly
    return 0;
  }
  const Matrix& W = eig.eigenvectors();
  y.setZero(S.rows(), S.cols());
  // Lower triangle of W diag(lambda) W^T, mirrored: exactly symmetric.
  y.template triangularView<Eigen::Lower>() = W * lambda.asDiagonal() * W.transpose();
  make_symmetric_from_lower(y);
  return clipped;
}

#define SPDFIT_INSTANTIATE(MaxN) \
  template Index nearest_spd_kernel<MaxN>(const SquareMatrix<MaxN>&, double, SquareMatrix<MaxN>&, double&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

NearestSpdResult nearest_spd(const Eigen::Ref<const MatrixXd>& X, double min_eig) {
  if (X.rows() != X.cols() || X.size() == 0) {
    throw std::invalid_argument("nearest_spd needs a non-empty square matrix, got " +
                                std::to_string(X.rows()) + "x" + std::to_string(X.cols()));
  }
  if (!X.allFinite()) throw std::invalid_argument("nearest_spd: the matrix contains NaN or Inf");
  if (!std::isfinite(min_eig) || min_eig < 0.0) {
    throw std::invalid_argument("nearest_spd: min_eig must be a finite number >= 0");
  }
  // Work in units where the largest entry (or min_eig) is in [0.5, 1) (exact: a power of two), so that the
  // eigenvalues, which can exceed the largest entry n times, do not overflow for entries near the
  // double range, and denormal input keeps its digits.
  const MatrixXd largest = MatrixXd::Constant(1, 1, std::max(X.cwiseAbs().maxCoeff(), min_eig));
  const int e = detail::scale_exponent(largest).value_or(0);
  const MatrixXd x = detail::times_power_of_two(X, -e);
  const double floor = std::ldexp(min_eig, -e);

  NearestSpdResult out;
  MatrixXd y;
  const Index clipped = detail::nearest_spd_kernel<Eigen::Dynamic>(x, floor, y, out.min_eigenvalue_before);
  if (clipped < 0) throw std::runtime_error("nearest_spd: the symmetric eigensolver did not converge");
  out.clipped = clipped;
  out.min_eigenvalue_before = std::ldexp(out.min_eigenvalue_before, e);
  out.distance = std::ldexp((x - y).stableNorm(), e);
  out.X = detail::times_power_of_two(y, e);
  if (!out.X.allFinite()) {
    // Possible only for a min_eig or entries within a factor n of the largest double.
    throw std::runtime_error("nearest_spd: the nearest matrix overflows the range of double precision numbers");
  }
  return out;
}

}  // namespace spdfit
