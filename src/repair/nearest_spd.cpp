#include "spdfit/nearest_spd.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "estimators/kernels.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
bool nearest_spd_kernel(const SquareMatrix<MaxN>& X, double min_eig, SquareMatrix<MaxN>& y,
                        NearestSpdInfo* info) {
  using Matrix = SquareMatrix<MaxN>;
  // Work in units where the largest entry (or min_eig) is in [0.5, 1) (exact: a power of two), so
  // that the eigenvalues, which can exceed the largest entry n times, do not overflow for entries
  // near the double range, and denormal input keeps its digits.
  const int e = scale_exponent(std::max(X.cwiseAbs().maxCoeff(), min_eig)).value_or(0);
  const Matrix x = times_power_of_two(X, -e);
  const double floor = std::ldexp(min_eig, -e);

  // Higham 1988: the nearest symmetric matrix is S = (X + X^T)/2, and the nearest one with
  // eigenvalues >= min_eig clips the eigenvalues of S = W diag(lambda) W^T. For min_eig = 0 this
  // is (S + H)/2 with H the symmetric polar factor of S (thesis eq. 4.39).
  const Matrix S = symmetric_part(x);
  Eigen::SelfAdjointEigenSolver<Matrix> eig(S);
  if (eig.info() != Eigen::Success) return false;
  typename BasicReduction<MaxN>::Vector lambda = eig.eigenvalues();
  const double min_before = lambda(0);
  Index clipped = 0;
  for (Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) < floor) {
      lambda(i) = floor;
      ++clipped;
    }
  }
  if (clipped == 0) {
    y = S;  // already admissible: no rounding from re-assembly
  } else {
    const Matrix& W = eig.eigenvectors();
    y.setZero(S.rows(), S.cols());
    // Lower triangle of W diag(lambda) W^T, mirrored: exactly symmetric.
    y.template triangularView<Eigen::Lower>() = W * lambda.asDiagonal() * W.transpose();
    make_symmetric_from_lower(y);
  }
  if (info) {
    info->clipped = clipped;
    info->min_before = std::ldexp(min_before, e);
    info->distance = std::ldexp((x - y).stableNorm(), e);
  }
  multiply_by_power_of_two(y, e);
  return true;
}

#define SPDFIT_INSTANTIATE(MaxN)                                                                 \
  template bool nearest_spd_kernel<MaxN>(const SquareMatrix<MaxN>&, double, SquareMatrix<MaxN>&, \
                                         NearestSpdInfo*);
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
  NearestSpdResult out;
  detail::NearestSpdInfo info;
  if (!detail::nearest_spd_kernel<Eigen::Dynamic>(X, min_eig, out.X, &info)) {
    throw std::runtime_error("nearest_spd: the symmetric eigensolver did not converge");
  }
  out.clipped = info.clipped;
  out.min_eigenvalue_before = info.min_before;
  out.distance = info.distance;
  if (!out.X.allFinite()) {
    // Possible only for a min_eig or entries within a factor n of the largest double.
    throw std::runtime_error(
        "nearest_spd: the nearest matrix overflows the range of double precision numbers");
  }
  return out;
}

}  // namespace spdfit
