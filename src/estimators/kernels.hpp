// Internal: the estimators' arithmetic, apart from their results' diagnostics and messages.
//
// Each kernel is a template over MaxN, the compile-time bound on n of BasicReduction: the
// public estimators instantiate it with Eigen::Dynamic (any n, heap matrices), the
// small-problem path (small_problem.hpp) with the bounds 2 and kSmallProblemMaxN (stack
// matrices, no heap allocation). Both run the same code, so they agree to rounding. The kernels
// are defined next to their estimator (spde.cpp, ...) and instantiated there for every bound in
// SPDFIT_FOR_EACH_MAX_N.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "spdfit/fit_result.hpp"

#include "factor/basic_reduction.hpp"

namespace spdfit::detail {

/// Least squares in scaled units: back substitution in R11 for full-rank A, else the
/// minimum-norm solution from the edited SVD.
template <int MaxN>
void least_squares_kernel(const BasicReduction<MaxN>& data, SquareMatrix<MaxN>& X_s);

/// Higham's closed form in the eigenbasis of R11^T R11 = V diag(s^2) V^T: the symmetric Xt
/// minimizing ||diag(s) Xt - C||_F, Xt_ij = (s_i C_ij + s_j C_ji) / (s_i^2 + s_j^2), and 0 where
/// s_i = s_j = 0 (free entries: the minimum-norm choice). Exactly symmetric.
template <typename Matrix, typename Vector>
void procrustes_eigenbasis(const Vector& s, const Matrix& C, Matrix& Xt) {
  const Eigen::Index n = s.size();
  Xt.resize(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = j; i < n; ++i) {
      const double denominator = s(i) * s(i) + s(j) * s(j);
      Xt(i, j) = denominator > 0.0 ? (s(i) * C(i, j) + s(j) * C(j, i)) / denominator : 0.0;
      Xt(j, i) = Xt(i, j);
    }
  }
}

/// Symmetric Procrustes (Higham's closed form) in scaled units, exactly symmetric.
template <int MaxN>
void procrustes_kernel(const BasicReduction<MaxN>& data, SquareMatrix<MaxN>& X_s);

/// SPDE in scaled units, for rank_a == n (else there is no minimizer): the positive
/// semidefinite X_s of rank rank_b. Returns the sum of the kept singular values of
/// M = R_b R11^T, tr(Sigma_Q~) of the area criterion's minimum (Corollary III.4).
template <int MaxN>
double spde_kernel(const BasicReduction<MaxN>& data, SquareMatrix<MaxN>& X_s);

/// Total least squares: X = -V12 V22^-1 from the SVD of R (V12 n x d, V22 d x d), in the scaled
/// units of the other estimators, and the quantities its diagnostics report (unscaled).
template <int MaxN>
struct TlsKernel {
  SquareMatrix<MaxN> X_s;   ///< when exists; n x d
  double sigma_n = 0.0;     ///< sigma_n of [A B]
  double sigma_n1 = 0.0;    ///< sigma_{n+1}
  double correction = 0.0;  ///< sqrt(sum_{i>n} sigma_i^2)
  double v22_min = 0.0;     ///< smallest singular value of V22 (d x d)
  bool exists = false;      ///< V22 nonsingular
  bool unique = false;      ///< sigma_n > sigma_{n+1} beyond rounding
  /// The noise estimate (noise_variance_from) from the same singular values; nothing when m <= n.
  std::optional<double> noise_var;
};
template <int MaxN>
void tls_kernel(const BasicReduction<MaxN>& data, TlsKernel<MaxN>& out);

/// What auto (auto.hpp) chooses, and the numbers it chose by.
struct AutoChoice {
  Method method = Method::Spde;
  const char* code = "";  ///< "rank_deficient_a", "noise_free", "many_samples" or "few_samples"
  double snr = 0.0;            ///< signal-to-noise ratio of A's weakest direction (NaN: unknown)
};

/// auto's choice between spde and spd-tls from the reduced data and the noise estimate (in A's
/// units; nothing when m <= n). O(1) given the noise estimate.
template <int MaxN>
AutoChoice auto_choice(const BasicReduction<MaxN>& data, std::optional<double> noise_var);

/// Whether the symmetric X is positive definite beyond rounding (auto's test of its choice):
/// lambda_min > 64 n eps lambda_max. False for an empty or non-finite X.
template <typename Matrix>
bool clearly_positive_definite(const Matrix& X);

/// auto's fallback floor for psd-ls, in scaled units: 1e-8 ||X_ls||_F (its least-squares
/// estimate), or the smallest normal number when that is 0.
template <int MaxN>
double auto_floor(const BasicReduction<MaxN>& data);

/// tls, tls-sym and tls-psd (in that order) from one TLS SVD, as the three public functions of
/// total_least_squares.hpp return them: what fit_all shares among the TLS family.
std::array<FitResult, 3> total_least_squares_family(const Reduction& reduction);

}  // namespace spdfit::detail
