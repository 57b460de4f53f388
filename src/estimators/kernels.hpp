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
#include "spdfit/nearest_spd.hpp"

#include "factor/basic_reduction.hpp"

namespace spdfit::detail {

/// Throws std::invalid_argument unless A is k x n, B is k x d, and both are finite (the data
/// checks of TriangularFactor, shared with the small-problem path).
void check_data(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                Eigen::Index n, Eigen::Index d);
/// check_data's two halves: the shapes, and NaN or Inf in A or B.
void check_shapes(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                  Eigen::Index n, Eigen::Index d);
void check_finite(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

/// The message for data with fewer rows m than columns n.
std::string too_few_rows(Eigen::Index m, Eigen::Index n);

/// The compile-time bounds on n the kernels are instantiated for: Eigen::Dynamic, and the small
/// bounds of small_problem.hpp.
#define SPDFIT_FOR_EACH_MAX_N(INSTANTIATE) INSTANTIATE(Eigen::Dynamic) INSTANTIATE(2) INSTANTIATE(8)

template <int MaxN>
using SquareMatrix = typename BasicReduction<MaxN>::Matrix;

/// Fills `out` (all but `options`, which the caller sets) from the (n + d) x (n + d) triangular
/// factor R of the data (A with n columns, B with d = R.cols() - n) scaled by 2^-exponent_a,
/// 2^-exponent_b, accumulated from m >= n rows: the SVD of R11, the triangular factor of B and
/// its singular values, the ranks. Cost O((n + d)^3). Without `vectors_a`, R11's singular
/// vectors U_a and V_a are left empty (uses_vectors_a says which methods need them).
template <int MaxN>
void reduce_into(const typename BasicReduction<MaxN>::Factor& R, Eigen::Index m, Eigen::Index n, int exponent_a,
                 int exponent_b, BasicReduction<MaxN>& out, bool vectors_a = true);

/// The reduction `method` needs and no more (reduce computes everything, for any method): for
/// one method's fit, without R11's singular vectors when the method does not use them.
Reduction reduce_for(const TriangularFactor& factor, const FitOptions& options, Method method);

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
};
template <int MaxN>
void tls_kernel(const BasicReduction<MaxN>& data, TlsKernel<MaxN>& out);

/// The (n + d) x (n + d) factor of [A, B / noise_ratio] in a common scaling 2^-e of A and B (what
/// TLS and the noise estimate decompose).
template <int MaxN>
void tls_factor(const BasicReduction<MaxN>& data, typename BasicReduction<MaxN>::Factor& R, int& e);

/// The noise estimate sigma^2 = sum_{i>n} s_i^2 / (d (m - n)), s_i the singular values of
/// [A, B / noise_ratio] in the data's units (of A): unbiased for independent noise of variance
/// sigma^2 in every entry of A (and noise_ratio^2 sigma^2 in B) when A_true X = B_true. Nothing
/// when m <= n. Cost O((n + d)^3).
template <int MaxN>
std::optional<double> noise_variance(const BasicReduction<MaxN>& data);

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
