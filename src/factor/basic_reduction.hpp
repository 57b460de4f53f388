// Internal: the reduced data the estimators' kernels work on, for a compile-time bound on n.
// Users see it only through spdfit::Reduction (spdfit/reduction.hpp), read-only.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "factor/data_cache.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/method.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit::detail {

/// The data reduced to small matrices, all in the scaled units of the triangular factor:
///
///   R11 = U_a diag(s_a) V_a^T        the SVD of R11: singular values of A, cond_a (rank_a is
///                                    decided on R11 with unit-norm columns, as A D)
///   [R12; R22] = Q_b R_b              R_b (d x d): B^T B = R_b^T R_b; singular values of B
///
/// B has d columns: d = n except for the n x d X of ls and tls (only they accept d != n).
///
/// Built by reduce_into (reduce.hpp) in O(n^3) from a triangular factor.
///
/// MaxN bounds n at compile time: the small-problem path (Monte Carlo experiments) uses
/// BasicReduction<2> and BasicReduction<kSmallProblemMaxN> whose matrices live on the stack; the public
/// spdfit::Reduction holds a BasicReduction<Eigen::Dynamic>.
/// The largest n of the small-problem path (small_problem.hpp), whose matrices live on the stack.
constexpr int kSmallProblemMaxN = 8;

/// The compile-time bounds on n the kernels are instantiated for: Eigen::Dynamic, and the small
/// bounds 2 and kSmallProblemMaxN. Each kernel's file instantiates it with
/// SPDFIT_FOR_EACH_MAX_N(ITS_INSTANTIATION_MACRO). A build without the small-problem kernels
/// (CMake's SPDFIT_SMALL_PROBLEM_KERNELS=OFF) instantiates Eigen::Dynamic only.
#ifdef SPDFIT_NO_SMALL_PROBLEM_KERNELS
#define SPDFIT_FOR_EACH_MAX_N(INSTANTIATE) INSTANTIATE(Eigen::Dynamic)
#else
#define SPDFIT_FOR_EACH_MAX_N(INSTANTIATE) \
  INSTANTIATE(Eigen::Dynamic) INSTANTIATE(2) INSTANTIATE(::spdfit::detail::kSmallProblemMaxN)
#endif

/// A reduction made by reduce (spdfit::Reduction) is owned by a shared_ptr: a result whose noise
/// estimate is read later (LazyOptional) keeps it alive through shared_from_this.
template <int MaxN = Eigen::Dynamic>
struct BasicReduction : std::enable_shared_from_this<BasicReduction<MaxN>> {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, MaxN, MaxN>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1>;
  /// The (n + d) x (n + d) triangular factor R of [A B].
  static constexpr int kMaxFactor = MaxN == Eigen::Dynamic ? Eigen::Dynamic : 2 * MaxN;
  using Factor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxFactor, kMaxFactor>;

  Eigen::Index m = 0, n = 0;
  Eigen::Index d = 0;                   ///< B's columns: X is n x d
  /// The data centred by their column means (a factor with an intercept, Offsets::Estimate): its
  /// m rows carry m - 1 degrees of freedom.
  bool centred = false;
  /// The rows' degrees of freedom: m, or m - 1 for centred data (what noise estimates divide by).
  Eigen::Index dof_rows() const { return centred ? m - 1 : m; }
  bool square() const { return d == n; }
  int exponent_a = 0, exponent_b = 0;   ///< data scaled by 2^-exponent (TriangularFactor)
  Matrix R11, R12, R22;                 ///< blocks of R: n x n, n x d, d x d (R22 zero-padded)
  Matrix U_a, V_a;                      ///< SVD of R11
  Vector s_a;                           ///< descending
  Matrix R_b;                           ///< triangular factor of B (d x d)
  Vector s_b;                           ///< singular values of B, descending
  /// Numerical ranks under the options' cut-off, decided on A and B with unit-norm columns.
  Eigen::Index rank_a = 0, rank_b = 0;
  /// cond(A D), cond(B D) with unit-norm columns where reduce_into computed them, else 0: where the
  /// rank needed the scaled singular values (cond(B D) only with options.reported_diagnostics),
  /// and cond(A D) with options.diagnostics where it may exceed 1 / kIllConditionedRcond, for the
  /// warning. The others are computed when a result's diagnostic is read (scaled_condition_of,
  /// reduce.hpp) and kept in the caches.
  double cond_a_scaled = 0.0, cond_b_scaled = 0.0;
  DataCache cond_a_cache, cond_b_cache;
  FitOptions options;
  /// The noise estimate sigma^2 (noise_variance, reduce.hpp), in A's units, once computed: ask
  /// data_noise_variance for it.
  DataCache noise_var;
};

/// A square matrix of at most MaxN rows (MaxN = Eigen::Dynamic: any).
template <int MaxN>
using SquareMatrix = typename BasicReduction<MaxN>::Matrix;

/// The lecture notes (002, section 3.7.2) call a matrix ill-conditioned when its reciprocal
/// condition number is below 1e-12: estimates may then have lost about 12 digits or more. The
/// warning about A is judged on cond(A D) (cond_a_scaled).
constexpr double kIllConditionedRcond = 1e-12;

/// The reduction behind the public, unbounded Reduction.
using DynamicReduction = BasicReduction<Eigen::Dynamic>;

/// The reduced data behind `reduction`. Throws std::invalid_argument for a default-constructed
/// Reduction (one not made by reduce).
inline const DynamicReduction& data_of(const Reduction& reduction) {
  if (!reduction.data_) throw std::invalid_argument("this Reduction is empty: make one with spdfit::reduce");
  return *reduction.data_;
}

/// Whether `method` works with R11's singular vectors (U_a, V_a): least squares, procrustes,
/// psd-ls and auto (which runs least squares). The others need only the singular values.
constexpr bool uses_vectors_a(Method method) {
  return method == Method::LeastSquares || method == Method::SymmetricProcrustes ||
         method == Method::PsdLeastSquares || method == Method::Auto;
}

/// Why `method` cannot use the noise model `model` (FitOptions::noise), or nothing when it can or
/// there is none (estimators/noise_weights.hpp says what each method needs).
std::optional<std::string> noise_refusal(const std::optional<NoiseModel>& model, Method method);

/// Throws noise_refusal's text for `method`: a usage error (OptionError) with Code::OptionNotApplicable
/// for spde (it takes no noise model) and Code::OptionValue for a model the method cannot use, but a
/// data error (InputError, Code::NoiseModel) where the rest rows are too few for the columns whose
/// covariance the method needs definite (N rows give rank N - 1 at most): the data's shortcoming,
/// not the request's.
[[noreturn]] void throw_noise_refusal(const std::string& why, Method method,
                                      const std::optional<NoiseModel>& model);

/// data_of for `method`: also throws std::invalid_argument when B's columns differ from A's and
/// the method does not fit a non-square X (non_square_refusal) or cannot use the noise model
/// (noise_refusal), and std::logic_error when the
/// reduction lacks R11's singular vectors the method needs (made by reduce_for another method).
inline const DynamicReduction& data_of(const Reduction& reduction, Method method) {
  const DynamicReduction& data = data_of(reduction);
  if (auto refusal = non_square_refusal(method, data.n, data.d)) throw std::invalid_argument(*refusal);
  if (auto refusal = noise_refusal(data.options.noise, method)) throw_noise_refusal(*refusal, method, data.options.noise);
  if (uses_vectors_a(method) && data.V_a.rows() != data.n) {
    throw std::logic_error(std::string("this Reduction was made for another method, without the singular vectors ") +
                           std::string(to_string(method)) + " needs: make one with spdfit::reduce");
  }
  return data;
}

}  // namespace spdfit::detail
