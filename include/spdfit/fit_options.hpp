// Knobs shared by every estimator.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>

#include "spdfit/rank.hpp"

namespace spdfit {

/// Options for the estimators. The defaults follow the source documents.
struct FitOptions {
  /// Relative cut-off for the numerical rank (spdfit/rank.hpp): a singular value sigma_i counts
  /// as zero when sigma_i <= rank_tolerance * sigma_max. A negative value (the default) means
  /// max(rows, cols) * machine epsilon, the editing rule of the lecture notes
  /// (shared/seeds/002, section 3.8).
  double rank_tolerance = -1.0;
  /// Compute the estimate's diagnostics (residual, eigenvalues, definiteness, area criterion)
  /// and the warnings about it. Monte Carlo loops that need only X turn this off: X is the same,
  /// bit for bit, without the two symmetric eigendecompositions and the residual per estimate.
  /// The data's diagnostics (m, n, ranks) and numerical failures are reported either way.
  bool diagnostics = true;
  /// The ratio sigma_B / sigma_A of the noise in B to the noise in A, for the total least-squares
  /// methods (tls, tls-sym, tls-psd, spd-tls, and auto): they fit [A, B / noise_ratio] and scale X back, so
  /// that the errors they minimize are in a common unit. Also the scaling of the noise estimate
  /// (Diagnostics::noise_sigma). A finite number > 0; 1 (the default) treats both alike.
  double noise_ratio = 1.0;
  /// The iterative methods (spd-tls, psd-ls, auto) stop after this many iterations at most, with
  /// the best iterate, converged = false and a warning. An integer >= 1.
  int max_iterations = 200;
  /// psd-ls: the floor epsilon of X >= epsilon I, in X's units. A finite number >= 0; 0 (the
  /// default) makes the result positive semidefinite, possibly singular.
  double min_eig = 0.0;

  /// True when the options are usable; otherwise `error` says why.
  bool is_valid(std::string* error = nullptr) const {
    if (!is_valid_rank_tolerance(rank_tolerance, "rank_tolerance", error)) return false;
    if (!(noise_ratio > 0.0) || !(noise_ratio < std::numeric_limits<double>::infinity())) {
      if (error) *error = "noise_ratio must be a finite number above 0";
      return false;
    }
    if (max_iterations < 1) {
      if (error) *error = "max_iterations must be at least 1";
      return false;
    }
    if (!(min_eig >= 0.0) || !(min_eig < std::numeric_limits<double>::infinity())) {
      if (error) *error = "min_eig must be a finite number >= 0";
      return false;
    }
    return true;
  }

  /// The cut-off to use for a rows x cols matrix (spdfit::rank_cutoff).
  double rank_cutoff(Eigen::Index rows, Eigen::Index cols) const {
    return spdfit::rank_cutoff(rank_tolerance, rows, cols);
  }
};

}  // namespace spdfit
