// Internal: Higham's nearest positive semidefinite matrix with an eigenvalue floor as a kernel
// templated on a bound for n (defined in nearest_spd.cpp for every bound of
// SPDFIT_FOR_EACH_MAX_N): nearest_spd runs it, and so do tls-psd and auto's repairs.
#pragma once

#include <Eigen/Core>

#include "factor/basic_reduction.hpp"
#include "spdfit/nearest_spd.hpp"

namespace spdfit::detail {

/// What nearest_spd_kernel reports besides the matrix.
struct NearestSpdInfo {
  Eigen::Index clipped = 0;   ///< eigenvalues raised to the floor
  double min_before = 0.0;    ///< smallest eigenvalue of the symmetric part, in X's units
  double max_before = 0.0;    ///< largest eigenvalue of the symmetric part, in X's units
  double min_eig = 0.0;       ///< the floor applied, in X's units (a relative floor resolved)
  double distance = 0.0;      ///< ||X - Y||_F
  double repair = 0.0;        ///< ||X - Y_0||_F, Y_0 the answer for the floor 0
  double floor_change = 0.0;  ///< ||Y - Y_0||_F, what the floor alone moved
};

/// Higham's nearest symmetric Y to X with eigenvalues >= the floor (see nearest_spd), computed
/// in units where the largest entry of X (or an absolute floor) is in [0.5, 1), an exact
/// power-of-two scaling, and written into y in X's units. X finite, the floor valid. Returns
/// false when the eigensolver did not converge, or when a relative floor meets a largest
/// eigenvalue <= 0 (info->max_before says which). `info`, when given, is filled (the distances
/// cost norms that the estimators do not need).
template <int MaxN>
bool nearest_spd_kernel(const SquareMatrix<MaxN>& X, EigenvalueFloor floor, SquareMatrix<MaxN>& y,
                        NearestSpdInfo* info = nullptr);

}  // namespace spdfit::detail
