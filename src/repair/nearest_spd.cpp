#include "spdfit/nearest_spd.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "repair/nearest_spd_kernel.hpp"
#include "spdfit/format.hpp"
#include "numerics/linalg.hpp"
#include "repair/repair.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
bool nearest_spd_kernel(const SquareMatrix<MaxN>& X, EigenvalueFloor floor, SquareMatrix<MaxN>& y,
                        NearestSpdInfo* info) {
  using Matrix = SquareMatrix<MaxN>;
  using Vector = typename BasicReduction<MaxN>::Vector;
  // Work in units where the largest entry (or an absolute floor) is in [0.5, 1) (exact: a power
  // of two), so that the eigenvalues, which can exceed the largest entry n times, do not overflow
  // for entries near the double range, and denormal input keeps its digits.
  const double absolute = floor.relative ? 0.0 : floor.value;
  const int e = scale_exponent(std::max(X.cwiseAbs().maxCoeff(), absolute)).value_or(0);
  const Matrix x = times_power_of_two(X, -e);

  // Higham 1988: the nearest symmetric matrix is S = (X + X^T)/2, and the nearest one with
  // eigenvalues >= the floor clips the eigenvalues of S = W diag(lambda) W^T. For the floor 0 this
  // is (S + H)/2 with H the symmetric polar factor of S (thesis eq. 4.39).
  const Matrix S = symmetric_part(x);
  Vector lambda;
  Matrix W;
  if (!symmetric_eigen(S, lambda, &W)) return false;
  const Index n = lambda.size();
  const double min_before = lambda(0), max_before = lambda(n - 1);
  if (info) {
    info->min_before = std::ldexp(min_before, e);
    info->max_before = std::ldexp(max_before, e);
  }
  if (floor.relative && floor.value > 0.0 && !(max_before > 0.0)) return false;
  const double scaled_floor = floor.relative ? floor.value * max_before : std::ldexp(floor.value, -e);
  Index clipped = 0;
  double repair = 0.0, floor_change = 0.0;  // squared, the parts of the clip below 0 and above
  for (Index i = 0; i < n; ++i) {
    if (lambda(i) < scaled_floor) {
      repair += std::pow(std::min(lambda(i), 0.0), 2);
      floor_change += std::pow(scaled_floor - std::max(lambda(i), 0.0), 2);
      lambda(i) = scaled_floor;
      ++clipped;
    }
  }
  if (clipped == 0) {
    y = S;  // already admissible: no rounding from re-assembly
  } else {
    y.setZero(S.rows(), S.cols());
    // Lower triangle of W diag(lambda) W^T, mirrored: exactly symmetric.
    y.template triangularView<Eigen::Lower>() = W * lambda.asDiagonal() * W.transpose();
    make_symmetric_from_lower(y);
  }
  if (info) {
    const double asymmetry_squared = (x - S).squaredNorm();
    info->clipped = clipped;
    info->min_eig = std::ldexp(scaled_floor, e);
    info->distance = std::ldexp((x - y).stableNorm(), e);
    info->repair = std::ldexp(std::sqrt(asymmetry_squared + repair), e);
    info->floor_change = std::ldexp(std::sqrt(floor_change), e);
  }
  multiply_by_power_of_two(y, e);
  return true;
}

#define SPDFIT_INSTANTIATE(MaxN)                                                                          \
  template bool nearest_spd_kernel<MaxN>(const SquareMatrix<MaxN>&, EigenvalueFloor, SquareMatrix<MaxN>&, \
                                         NearestSpdInfo*);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

NearestResult nearest_spd(const Eigen::Ref<const MatrixXd>& X, EigenvalueFloor floor) {
  detail::check_repair_input(X, floor);
  NearestResult out;
  detail::NearestSpdInfo info;
  info.max_before = std::numeric_limits<double>::quiet_NaN();  // set once the eigenvalues are known
  if (!detail::nearest_spd_kernel<Eigen::Dynamic>(X, floor, out.X, &info)) {
    // A relative floor without a positive eigenvalue to be relative to: resolve_floor says so.
    if (!std::isnan(info.max_before)) detail::resolve_floor(floor, info.max_before);
    throw std::runtime_error("repairing the matrix: the symmetric eigensolver did not converge");
  }
  if (!out.X.allFinite()) {
    // Possible only for a min_eig or entries within a factor n of the largest double.
    throw std::runtime_error("the repaired matrix overflows the range of double precision numbers");
  }
  out.clipped = info.clipped;
  out.min_eigenvalue_before = info.min_before;
  out.min_eig = info.min_eig;
  out.distance = info.distance;
  out.cholesky_ok = detail::has_cholesky(out.X);
  if (auto w = detail::asymmetry_warning(X)) out.warnings.push_back(*w);
  if (auto w = detail::floor_warning(info.min_eig, info.floor_change, info.repair, X.norm(), info.max_before)) {
    out.warnings.push_back(*w);
  }
  if (out.clipped > 0) {
    // The repair changed the spectrum: say how much of it, so that a user who expected an
    // already valid matrix learns that it was not.
    out.warnings.push_back(Warning(Code::EigenvaluesRaised, std::to_string(out.clipped) + " eigenvalue(s) of the symmetric part were below " +
                           format_number(out.min_eig) +
                           (floor.relative ? " (" + format_number(floor.value) + " x the largest eigenvalue)" : "") +
                           " and were raised to it"));
  }
  return out;
}

NearestResult nearest_spd(const Eigen::Ref<const MatrixXd>& X, double min_eig) {
  return nearest_spd(X, EigenvalueFloor::absolute(min_eig));
}

}  // namespace spdfit
