// What an estimator returns: the estimate and the evidence a user checks it by.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/outcome.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/lazy_optional.hpp"
#include "spdfit/method.hpp"
#include "spdfit/noise_model.hpp"

namespace spdfit {

/// Whether an estimator produced an estimate. Misuse of the API (wrong shapes, NaN input)
/// throws std::invalid_argument instead; a status is for valid input that has no answer.
enum class Status {
  NotComputed,       ///< no estimator has filled this result (a default-constructed FitResult)
  Success,
  NumericalFailure,  ///< e.g. V22 singular in TLS, A rank-deficient in SPDE; see `message`
};

/// The status's name in Python and JSON: "not_computed", "success" or "numerical_failure".
constexpr const char* to_string(Status status) {
  switch (status) {
    case Status::NotComputed:
      return "not_computed";
    case Status::Success:
      return "success";
    case Status::NumericalFailure:
      return "numerical_failure";
  }
  return "unknown";
}

/// psd-ls's proof of optimality: the KKT conditions of minimizing ||A X - B||_F^2 / 2 over
/// symmetric X >= epsilon I, with the multiplier S = sym(A^T A X - A^T B) (from the triangular
/// factor); with a noise model (FitOptions::noise) of the weighted sum_i r_i^T Sigma_B^-1 r_i / 2,
/// r_i the rows of A X - B, with S = sym(A^T (A X - B) Sigma_B^-1). X is optimal exactly when
/// primal_min_eig >= 0, dual_min_eig >= 0 and complementarity = 0; the numbers say how far from
/// that the returned X is, in the data's units.
struct PsdCertificate {
  double primal_min_eig = 0.0;   ///< lambda_min(X - epsilon I)
  double dual_min_eig = 0.0;     ///< lambda_min(S)
  double complementarity = 0.0;  ///< <X - epsilon I, S>
  /// The relative duality gap |<X - epsilon I, S>| / (||A^T A||_2 ||X||_F + ||A^T B||_F):
  /// the objective's distance from its lower bound when S >= 0 (dimensionless).
  double duality_gap = 0.0;
};

/// spd-tls's proof of optimality on the boundary (where its criterion f, the likelihood with a
/// noise model and the TLS criterion without, has no minimizer over the positive definite
/// matrices and the estimate is the X of rank r < n minimizing it over the positive semidefinite
/// ones): the first-order (KKT) conditions of that constrained problem. With X = V_r Lambda V_r^T (V_0 an orthonormal
/// basis of its null space) and G = grad f(X), X satisfies them exactly when
/// Lambda^1/2 V_r^T G V_r Lambda^1/2 = 0 (stationarity on the face), V_r^T G V_0 = 0 (the cross
/// block: turning X's range does not lower f) and V_0^T G V_0 >= 0 (the multiplier of X >= 0:
/// growing X into its null space does not lower f). Every number is computed in the coordinates
/// where X has a unit diagonal (X -> D^-1 X D^-1, G -> D G D, D = diag(X)^1/2), so that a change
/// of units A -> A E, B -> B E^-1 leaves it alone, and relative to f (dimensionless).
struct BoundaryCertificate {
  Eigen::Index rank = 0;            ///< r, X's rank
  double stationarity = 0.0;        ///< ||Lambda^1/2 V_r^T G V_r Lambda^1/2||_F / f
  double cross_block = 0.0;         ///< ||Lambda^1/2 V_r^T G V_0||_F / f
  double multiplier_min_eig = 0.0;  ///< lambda_min(V_0^T G V_0) / f, >= 0 at the optimum
};

/// Why `auto` chose its method: a stable code for scripts and a sentence for people.
struct AutoReason {
  std::string code;  ///< "few_samples", "many_samples", "noise_free", "rank_deficient_a" or "boundary"
  std::string text;
};

/// Quantities a user checks an estimate by. Singular values, ranks and condition numbers
/// are those of the data A and B (computed from the triangular factor, not Gram matrices).
/// Optional entries are present only where they are defined for the method and estimate.
struct Diagnostics {
  Eigen::Index m = 0;                                    ///< rows (samples)
  Eigen::Index n = 0;                                    ///< A's columns; X is n x d
  Eigen::Index d = 0;                                    ///< B's columns (d = n but for ls and tls)
  /// Numerical ranks (FitOptions::rank_tolerance), decided on A and B with their columns scaled
  /// to unit norm (by powers of two), so that they do not depend on each column's units.
  Eigen::Index rank_a = 0, rank_b = 0;
  double cond_a = 0.0, cond_b = 0.0;                     ///< sigma_max / sigma_min; +inf when singular
  /// The condition numbers of A and B with unit-norm columns: those the ranks are decided on,
  /// and the ones that bound the estimate's loss of accuracy. 0 when not computed
  /// (FitOptions::reported_diagnostics off). Each costs an SVD of an n x n matrix when the rank
  /// did not need one: it is then computed when first read (it reads like a double; the number
  /// does not depend on when it is read, see LazyOptional), and kept for every copy.
  LazyDouble cond_a_scaled = 0.0, cond_b_scaled = 0.0;
  Eigen::VectorXd singular_values_a, singular_values_b;  ///< descending

  double residual_norm = 0.0;            ///< ||A X - B||_F
  bool symmetric = false;                ///< X == X^T exactly
  std::optional<double> min_eigenvalue;  ///< of X, when X is symmetric
  std::optional<double> max_eigenvalue;  ///< of X, when X is symmetric
  bool positive_definite = false;        ///< X symmetric with every eigenvalue > 0
  bool positive_semidefinite = false;    ///< X symmetric, eigenvalues >= -4 n eps max|lambda| (rounding)

  /// The area criterion ||A Y - B Y^-T||_F^2 with X = Y Y^T (Chen & McInroy, Definition II.1),
  /// for a symmetric positive definite X; for a semidefinite X of rank r the criterion
  /// tr(P X + X^+ Q) - 2 tr(A^T B) of Corollary III.7.
  std::optional<double> area_criterion;
  /// spde only: the closed-form minimum 2 tr(Sigma_Q~ - A^T B) (Corollary III.4 / III.7).
  std::optional<double> area_criterion_minimum;

  /// procrustes only: whether A^T B + B^T A is positive definite (thesis Theorem 3.2 (3):
  /// then the estimate is too).
  std::optional<bool> cross_term_positive_definite;

  /// TLS family: singular values sigma_n and sigma_{n+1} of [A B], the correction norm
  /// ||[dA dB]||_F = sqrt(sum_{i>n} sigma_i^2) (thesis eq. 4.33), and the smallest
  /// singular value of V22 (the solution exists when it is nonzero).
  std::optional<double> tls_sigma_n, tls_sigma_n1, tls_correction_norm, tls_v22_min_singular_value;

  /// The noise estimate: the standard deviation sigma of independent noise in every entry of A
  /// (noise_ratio * sigma in B, FitOptions::noise_ratio) under the TLS model A_true X = B_true,
  /// from sigma^2 = sum_{i>n} s_i^2 / (d (m - n)), s_i the singular values of [A, B / noise_ratio]
  /// (unbiased for sigma^2). Present whenever m > n, for every method; its relative standard
  /// error is about sqrt(2 / (d (m - n))), and a warning says so when m - n < n. It is the
  /// equal-noise model's estimate: with a noise model (`noise_model`) the text report leaves it
  /// out and no warning is about it.
  /// It costs a values-only SVD of that (n + d) x (n + d) factor, longer than spde's or
  /// procrustes' whole estimate at large n, so a fit computes it when it is first read (it reads
  /// like std::optional<double>; the number does not depend on when it is read): once for every
  /// copy of the result and for every method fitted from the same Reduction, and never for a fit
  /// whose reader does not look at it (JSON and text reports read it). tls, tls-sym and tls-psd
  /// without a noise model take it from the SVD of the same factor they compute for X (with
  /// right singular vectors; above 64 columns its last bits may differ from the values-only SVD's).
  /// Until it is read, the result keeps the fit's reduced data alive (about 6 n^2 numbers).
  LazyOptional noise_sigma;

  /// The iterative methods (spd-tls, psd-ls): iterations taken, the final stopping quantity
  /// (spd-tls: ||X^1/2 grad f(X) X^1/2||_F in the units of the criterion; psd-ls: the relative
  /// KKT residual), and whether the stopping rule held.
  std::optional<int> iterations;
  std::optional<double> gradient_norm;
  std::optional<bool> converged;
  /// psd-ls only: the optimality certificate.
  std::optional<PsdCertificate> certificate;
  /// spd-tls (and auto when it returned spd-tls's estimate), when the estimate is on the boundary
  /// (singular): the constrained problem's first-order conditions. The JSON's "certificate" too.
  std::optional<BoundaryCertificate> boundary_certificate;
  /// The noise model the estimate used (FitOptions::noise, resolved to n x n and d x d covariances
  /// in the data's units), with its source; empty when none was given or the method ran without
  /// it (spde in fit_all): the methods then assume equal noise in every column of A and B, in the
  /// units given (reports say "assumed-equal").
  std::optional<NoiseModel> noise_model;
  /// auto only: the method it ran (also the result's `method`) and why.
  std::optional<Method> chosen_method;
  std::optional<AutoReason> reason;
};

/// A two-sided bootstrap interval for each entry, of the kind `type` (FitOptions::interval). With
/// q_lo and q_hi the (1 - level) / 2 and (1 + level) / 2 quantiles of the replicates (linear
/// interpolation between order statistics, as numpy.quantile's default): percentile [q_lo, q_hi];
/// basic [2 X - q_hi, 2 X - q_lo]; normal X - bias -+ z se (Bootstrap::bias, standard_errors; z
/// the standard normal quantile at (1 + level) / 2).
struct Interval {
  double level = 0.95;
  BootstrapInterval type = BootstrapInterval::Percentile;
  Eigen::MatrixXd lower, upper;
};

/// The bootstrap uncertainty of values sorted in ascending order (the eigenvalues of X, a
/// hexapod's modes). Values closer than their standard errors swap places between replicates,
/// so the sorted values' own intervals are biased there: such values form one cluster, and each
/// member's lower and upper are the cluster's (the lower quantile of its smallest value, the upper
/// quantile of its largest).
struct SpectrumUncertainty {
  Eigen::VectorXd estimate;         ///< the values of the estimate, ascending
  Eigen::VectorXd standard_errors;  ///< of each sorted value over the replicates
  Eigen::VectorXd lower, upper;     ///< the interval (the cluster's, for clustered values)
  /// Consecutive indices of values closer than their standard errors; singletons included.
  std::vector<std::vector<Eigen::Index>> clusters;
  int failed = 0;  ///< replicates without the values (not symmetric, not positive definite)
};

/// How sure the estimate is: the nonparametric bootstrap over the rows of [A B]
/// (FitOptions::bootstrap).
struct Bootstrap {
  int replicates = 0;        ///< requested (FitOptions::bootstrap)
  int failed = 0;            ///< replicates without an estimate, left out of everything below
  std::uint64_t seed = 1;    ///< FitOptions::seed
  Method method = Method::Spde;  ///< the method every replicate ran (auto: the one it chose)
  /// "multinomial": each replicate draws m rows with replacement (in memory); "poisson_groups":
  /// each group of group_rows consecutive rows gets a Poisson(1) count per replicate (streaming).
  std::string scheme = "multinomial";
  Eigen::Index group_rows = 0, groups = 0;  ///< poisson_groups only
  Eigen::MatrixXd standard_errors;  ///< per entry: the replicates' standard deviation (divisor N - 1)
  Eigen::MatrixXd bias;             ///< per entry: the replicates' mean minus the estimate
  Interval interval;                ///< per entry, at FitOptions::confidence
  std::optional<SpectrumUncertainty> eigenvalues;  ///< when the estimate is symmetric
};

/// The constant offsets a fit took out of the data (FitOptions::offsets other than None).
struct FitOffsets {
  Offsets mode = Offsets::None;
  /// Estimate: c = mu_B - X^T mu_A (d numbers, in B's units), the constants of A X + 1 c^T ~= B,
  /// mu_A and mu_B the column means of A and B.
  Eigen::VectorXd c;
  /// Rest: the rest rows' means subtracted from A (n) and from B (d).
  Eigen::VectorXd a, b;
};

/// What a robust fit (FitOptions::robust) did to the rows.
struct RobustReport {
  RobustLoss method = RobustLoss::None;
  double tuning = 0.0;  ///< the loss's constant k
  double scale = 0.0;   ///< the robust scale of the whitened residual norms (their median over the chi median)
  /// The rows (1-based, as the data's) whose final weight is below 0.5: at most 1000 listed, all counted.
  std::vector<std::uint64_t> rows_downweighted;
  std::uint64_t rows_downweighted_count = 0;
  double weights_min = 1.0;  ///< the smallest final weight
  int iterations = 0;        ///< reweighting iterations
  bool converged = true;     ///< the weights settled within FitOptions::max_iterations
};

/// The result of one estimator on one data set.
struct FitResult {
  Method method = Method::Spde;
  Status status = Status::NotComputed;  ///< an estimator sets Success or NumericalFailure
  std::string message;  ///< why it failed, when status != Success
  Eigen::MatrixXd X;    ///< the estimate (empty on failure)
  Diagnostics diagnostics;
  std::vector<Warning> warnings;  ///< conditions the user should know about
  /// The bootstrap's standard errors, interval and bias, when FitOptions::bootstrap > 0 and the
  /// estimate succeeded.
  std::optional<Bootstrap> bootstrap;
  /// The names of X's rows (A's columns) and columns (B's columns), from the header rows of the
  /// files fit_files read (a dropped index column's name left out); empty when a file had none.
  std::vector<std::string> row_names, column_names;
  /// A and B from one file (FitRequest::a_cols, b_cols): the file and the columns each came from,
  /// "log.csv columns acc1..acc6 (2-7)"; empty when each came from a file of its own.
  std::string a_columns, b_columns;
  /// The offsets taken out of the data (FitOptions::offsets Estimate or Rest); nothing without.
  std::optional<FitOffsets> offsets;
  /// What the robust fit did (FitOptions::robust other than None); nothing without.
  std::optional<RobustReport> robust;

  bool ok() const { return status == Status::Success; }
};

}  // namespace spdfit
