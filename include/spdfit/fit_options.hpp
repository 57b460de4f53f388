// Knobs shared by every estimator.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>
#include <string>
#include <string_view>

#include "spdfit/noise_model.hpp"
#include "spdfit/progress.hpp"
#include "spdfit/rank.hpp"

namespace spdfit {

/// Constant offsets in the data's columns (FitOptions::offsets): a static load in forces logged
/// untared, an accelerometer's bias.
enum class Offsets {
  None,      ///< the model A X ~= B as the data are given
  Estimate,  ///< A X + 1 c^T ~= B, unknown constants in A's and B's columns fitted with X
  Rest,      ///< the rest rows' means (the noise model's, NoiseModel::from_rest) subtracted first
};

/// "none", "estimate" or "rest".
inline const char* to_string(Offsets offsets) {
  return offsets == Offsets::Estimate ? "estimate" : offsets == Offsets::Rest ? "rest" : "none";
}

/// The mode to_string spells `name`, or nothing.
inline std::optional<Offsets> offsets_named(std::string_view name) {
  for (Offsets o : {Offsets::None, Offsets::Estimate, Offsets::Rest}) {
    if (name == to_string(o)) return o;
  }
  return std::nullopt;
}

/// A robust fit's loss (FitOptions::robust): how a row's weight falls with its whitened residual.
enum class RobustLoss {
  None,   ///< every row weighs 1 (least squares and the methods as they are)
  Huber,  ///< weight min(1, k / u): large residuals count linearly, not squared
  Tukey,  ///< weight (1 - (u / k)^2)^2 below k, 0 beyond: gross errors count not at all
};

/// "none", "huber" or "tukey".
inline const char* to_string(RobustLoss loss) {
  return loss == RobustLoss::Huber ? "huber" : loss == RobustLoss::Tukey ? "tukey" : "none";
}

/// The loss to_string spells `name`, or nothing.
inline std::optional<RobustLoss> robust_loss_named(std::string_view name) {
  for (RobustLoss loss : {RobustLoss::None, RobustLoss::Huber, RobustLoss::Tukey}) {
    if (name == to_string(loss)) return loss;
  }
  return std::nullopt;
}

/// The bootstrap interval of each entry of X (FitOptions::interval), from the replicates'
/// quantiles q_lo, q_hi (at (1 - level) / 2 and (1 + level) / 2), their mean and standard error.
enum class BootstrapInterval {
  Percentile,  ///< [q_lo, q_hi]: the replicates' central fraction as it is
  Basic,       ///< [2 X - q_hi, 2 X - q_lo]: the percentile interval reflected about the estimate,
               ///< which corrects the estimate's bias (same width); better near the SPD boundary
  Normal,      ///< (X - bias) -+ z se, z the normal quantile at (1 + level) / 2
  /// Basic where the positive semidefinite constraint is active (X, or at least
  /// kBoundaryReplicateFraction of the replicates, singular: kSingularRelative), else
  /// percentile. Only asked for: an Interval's type is the one computed.
  Auto,
};

/// An X is singular, on the boundary of the positive semidefinite cone, when its smallest
/// eigenvalue (less psd-ls's floor min_eig) is within this times its largest of 0: spd-tls's and
/// psd-ls's boundary estimates are singular to rounding, ~1e-16; an indefinite X is not.
inline constexpr double kSingularRelative = 1e-10;

/// BootstrapInterval::Auto takes the basic interval when at least this fraction of the replicates
/// is singular, even where X is not.
inline constexpr double kBoundaryReplicateFraction = 0.1;

/// "percentile", "basic", "normal" or "auto".
inline const char* to_string(BootstrapInterval type) {
  switch (type) {
    case BootstrapInterval::Basic:
      return "basic";
    case BootstrapInterval::Normal:
      return "normal";
    case BootstrapInterval::Auto:
      return "auto";
    case BootstrapInterval::Percentile:
      break;
  }
  return "percentile";
}

/// The interval to_string spells `name`, or nothing.
inline std::optional<BootstrapInterval> bootstrap_interval_named(std::string_view name) {
  for (BootstrapInterval t : {BootstrapInterval::Percentile, BootstrapInterval::Basic,
                              BootstrapInterval::Normal, BootstrapInterval::Auto}) {
    if (name == to_string(t)) return t;
  }
  return std::nullopt;
}

/// Options for the estimators. The defaults follow the source documents.
struct FitOptions {
  /// Relative cut-off for the numerical rank (spdfit/rank.hpp): a singular value sigma_i counts
  /// as zero when sigma_i <= rank_tolerance * sigma_max. Nothing (the default) means
  /// max(rows, cols) * machine epsilon, the editing rule of the lecture notes
  /// (shared/seeds/002, section 3.8). A number in [0, 1).
  std::optional<double> rank_tolerance;
  /// Compute the estimate's diagnostics (residual, eigenvalues, definiteness, area criterion)
  /// and the warnings about it. Monte Carlo loops that need only X turn this off: X is the same,
  /// bit for bit, without the two symmetric eigendecompositions and the residual per estimate.
  /// The data's diagnostics (m, n, ranks) and numerical failures are reported either way.
  bool diagnostics = true;
  /// With diagnostics, also compute the diagnostics that are only reported, which neither X nor a
  /// warning needs: the noise estimate (Diagnostics::noise_sigma, the singular values of the
  /// (n + d) x (n + d) triangular factor of [A B]), the column-scaled condition numbers
  /// (cond_a_scaled, cond_b_scaled: singular values of A and B with scaled columns), the residual
  /// norm and the area criterion (products of n x n matrices). On, the noise estimate and the
  /// scaled condition numbers (where the ranks did not need them) are computed when first read
  /// (LazyOptional, LazyDouble): a fit nobody reads them from does not pay for their SVDs.
  /// Off, noise_sigma and area_criterion are unset, residual_norm and cond_b_scaled are 0, and so
  /// is cond_a_scaled unless it may exceed 1e12 (then it is computed for the warning about an
  /// ill-conditioned A); procrustes computes cross_term_positive_definite only for its warning.
  /// X, the ranks, the eigenvalues and definiteness of X are the same, and so are the warnings
  /// but the one about a noise estimate from few rows. auto and the bootstrap compute the noise
  /// estimate they need either way. The command line turns this off when it prints X alone.
  bool reported_diagnostics = true;
  /// The ratio sigma_B / sigma_A of the noise in B to the noise in A, for the total least-squares
  /// methods (tls, tls-sym, tls-psd, spd-tls, and auto): they fit [A, B / noise_ratio] and scale X back, so
  /// that the errors they minimize are in a common unit. Also the scaling of the noise estimate
  /// (Diagnostics::noise_sigma). A finite number > 0; 1 (the default) treats both alike.
  double noise_ratio = 1.0;
  /// The noise model (noise_model.hpp): the covariances of the noise in each row of A and of B.
  /// Without one the methods assume equal, independent noise in every column of A and B, in the
  /// units given (noise_ratio scales B's). With one, spd-tls is the maximum-likelihood estimate
  /// over the positive definite matrices, psd-ls and procrustes are weighted by B's covariance,
  /// tls, tls-sym and tls-psd are generalized total least squares, auto chooses with it, ls is
  /// A^+ B whatever the weight, and spde (which has none) refuses it. Checked against the data's
  /// sizes when the data are reduced (NoiseModel::resolved). Not together with noise_ratio != 1.
  std::optional<NoiseModel> noise;
  /// Units: every column of A multiplied by scale_a as the data are read (one factor for every
  /// column, or one per column; empty, the default: as given), and B's by scale_b, so that data
  /// logged in other units are fitted in the ones wanted (forces in kN: scale_b = {1000}; X is then
  /// in N per unit of A). The noise model describes the data as given (rest rows, standard
  /// deviations and covariances in the files' units) and is scaled with them. Each factor a finite
  /// number > 0; a count other than 1, n (d) is refused when the data are fitted. fit(A, B, ...),
  /// fit_all(A, B, ...) and fit_files apply them (also streamed); the overloads taking a Reduction
  /// or a TriangularFactor have data already factored and refuse them.
  std::vector<double> scale_a, scale_b;
  /// Constant offsets in the columns of A and B. None (the default): the data as given. Estimate:
  /// the model A X + 1 c^T ~= B, errors in variables with intercepts (only c = mu_B - X^T mu_A,
  /// d numbers, is identifiable, not A's and B's offsets apart): the estimators see the data
  /// centred by their column means (the triangular factor of [1 A B], TriangularFactor with an
  /// intercept), the noise estimate counts the degree of freedom lost, and FitResult::offsets has
  /// c. Rest: the means of the rows recorded at rest (the noise model's, which must come from
  /// rest rows) are subtracted from A and B (taring); FitResult::offsets has them. fit(A, B, ...),
  /// fit_all(A, B, ...) and fit_files apply them (also streamed); the overloads taking a Reduction
  /// take a factor with an intercept for Estimate and refuse Rest.
  Offsets offsets = Offsets::None;
  /// A robust fit (an M-estimator of X by iteratively reweighted rows, each row weighed by its
  /// residual whitened by the noise model and scaled by the residuals' robust scale): for ls,
  /// procrustes, psd-ls, spd-tls, tls, tls-sym, tls-psd and auto (choosing among them), in memory
  /// (fit(A, B, ...), fit_files without streaming); spde (no rows in its criterion), a Reduction and
  /// a stream (one pass cannot reweigh rows) refuse it. Huber starts from the plain fit; Tukey from
  /// least trimmed squares on the rows, so that wrong rows of A (leverage points) cannot capture
  /// it. FitResult::robust reports the weights. None (the default): the plain fit.
  RobustLoss robust = RobustLoss::None;
  /// The loss's constant k, in standard deviations of a row's whitened residual norm; nothing (the
  /// default): the constant giving 95% of least squares' efficiency at Gaussian noise for B's d
  /// columns (d = 1: Huber's 1.345, Tukey's 4.685). A finite number > 0.
  std::optional<double> robust_tuning;
  /// The iterative methods (spd-tls, psd-ls, auto) stop after this many iterations at most, with
  /// the best iterate, converged = false and a warning. An integer >= 1.
  int max_iterations = 200;
  /// psd-ls: the floor epsilon of X >= epsilon I, in X's units. A finite number >= 0; 0 (the
  /// default) makes the result positive semidefinite, possibly singular.
  double min_eig = 0.0;
  /// Bootstrap replicates for the uncertainty of X (FitResult::bootstrap): 0 (the default) for
  /// none. With N > 0, fit(A, B, ...) and fit_files resample the rows of [A B] N times and
  /// refit each resample with the same method (auto: the method it chose on the full data). An
  /// integer >= 0. The overloads taking a Reduction have no rows to resample and ignore it.
  int bootstrap = 0;
  /// The bootstrap's two-sided interval covers this fraction: in (0, 1), default 0.95.
  double confidence = 0.95;
  /// The bootstrap interval of each entry of X (Bootstrap::interval): auto (the default: basic
  /// where X or many replicates are on the boundary of the cone, else percentile), percentile,
  /// basic or normal. The sorted values' intervals (eigenvalues, modes) stay percentile intervals.
  BootstrapInterval interval = BootstrapInterval::Auto;
  /// The bootstrap's seed: replicate r draws from a generator keyed by (seed, r), so the numbers
  /// depend on nothing else (not on the number of threads).
  std::uint64_t seed = 1;
  /// Threads for the bootstrap's replicates: 0 (the default) means one per core.
  unsigned threads = 0;
  /// Told the fraction of the bootstrap's replicates refitted, as they finish.
  ProgressCallback progress;

  /// True when every option is in the range fit_option_table() gives it (fit_request.hpp) and a
  /// noise model does not come with noise_ratio != 1; otherwise `error` names the option and says
  /// why.
  bool is_valid(std::string* error = nullptr) const;

  /// The cut-off to use for a rows x cols matrix (spdfit::rank_cutoff).
  double rank_cutoff(Eigen::Index rows, Eigen::Index cols) const {
    return rank_tolerance ? *rank_tolerance : default_rank_tolerance(rows, cols);
  }
};

}  // namespace spdfit
