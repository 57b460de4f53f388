// The spectral quantities of A and B that several estimators share, computed once from
// the triangular factor.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_options.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit {

/// The data reduced to small matrices, all in the scaled units of the triangular factor:
///
///   R11 = U_a diag(s_a) V_a^T        the SVD of R11: singular values of A, rank_a, cond_a
///   [R12; R22] = Q_b R_b              R_b (n x n): B^T B = R_b^T R_b; singular values of B
///
/// Built by `reduce` in O(n^3) from a TriangularFactor. Estimators taking a Reduction are the
/// careful path; the overloads taking A and B call TriangularFactor::from_data and reduce.
///
/// MaxN bounds n at compile time: the library's small-problem path (Monte Carlo experiments)
/// uses BasicReduction<2> and BasicReduction<8> whose matrices live on the stack. User code needs
/// only `Reduction`, the unbounded one.
template <int MaxN = Eigen::Dynamic>
struct BasicReduction {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, MaxN, MaxN>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1>;
  /// The 2n x 2n triangular factor R of [A B].
  static constexpr int kMaxFactor = MaxN == Eigen::Dynamic ? Eigen::Dynamic : 2 * MaxN;
  using Factor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxFactor, kMaxFactor>;

  Eigen::Index m = 0, n = 0;
  int exponent_a = 0, exponent_b = 0;   ///< data scaled by 2^-exponent (TriangularFactor)
  Matrix R11, R12, R22;                 ///< n x n blocks of R (R22 zero-padded)
  Matrix U_a, V_a;                      ///< SVD of R11
  Vector s_a;                           ///< descending
  Matrix R_b;                           ///< triangular factor of B
  Vector s_b;                           ///< singular values of B, descending
  Eigen::Index rank_a = 0, rank_b = 0;  ///< numerical ranks under the options' cut-off
  FitOptions options;
};

/// The reduction for any n (dynamic matrices).
using Reduction = BasicReduction<>;

/// Reduces the factor for the estimators. Throws std::invalid_argument when the factor has
/// fewer rows than columns (m < n) or the options are invalid. Cost O(n^3).
Reduction reduce(const TriangularFactor& factor, const FitOptions& options = {});

}  // namespace spdfit
