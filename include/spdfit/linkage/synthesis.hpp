// Approximate and exact synthesis of a planar 4R function generator: design error, structural
// error, precision points and dial zeros (notes 002, sections 3.3.3-3.6).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/outcome.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/freudenstein.hpp"
#include "spdfit/linkage/prescribed_function.hpp"
#include "spdfit/linkage/status.hpp"
#include "spdfit/linkage/structural_error.hpp"

namespace spdfit::linkage {

/// Options for synthesize().
#pragma GCC diagnostic push
// The deprecated field below must not warn in the copies the compiler writes for every user.
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
struct SynthesisOptions {
  /// Dial zeros (eq. 3.6, radians): psi = alpha + delta_psi, phi = beta + delta_phi. Absent
  /// means 0, so that the pairs are the absolute angles. With fit_dial_zeros, present values are
  /// the starting guess instead (both default to 0 when only one is given).
  std::optional<double> alpha, beta;
  /// Also solve for alpha and beta (5 unknowns, eq. 3.7) by nonlinear least squares. Without a
  /// starting guess, every (alpha, beta) on a 5-degree grid is tried and the one whose
  /// design-error linkage has the smallest structural error (preferring linkages without a dead
  /// point in the swept input range) is the start.
  bool fit_dial_zeros = false;
  /// Run the structural-error Gauss-Newton refinement (section 3.6) after the design solution.
  bool refine = true;
  GaussNewtonOptions gauss_newton;
  /// Relative singular-value cut-off for the synthesis matrix (nothing: max(m, n) eps, notes 3.8).
  std::optional<double> rank_tolerance;
  /// The old name of rank_tolerance (negative: the default), used when rank_tolerance is not set;
  /// removed in the next release.
  [[deprecated("use rank_tolerance")]] double threshold = -1.0;

  bool is_valid(std::string* error = nullptr) const;
};
#pragma GCC diagnostic pop

/// One solution: the parameters, the linkage, and its errors.
struct LinkageSolution {
  Eigen::Vector3d k = Eigen::Vector3d::Zero();
  DialZeros dial_zeros;               ///< used (fitted ones with fit_dial_zeros)
  std::optional<FourBar> lengths;     ///< a1 = 1; absent when k has no real linkage
  std::string no_linkage_reason;      ///< why lengths is absent
  double design_error_norm = 0.0;     ///< (d^T W d)^(1/2) at this k (eq. 3.8-3.10)
  /// Structural error s = phi_pres - phi_gen (radians): RMS (unweighted) and max |s_i|. NaN when
  /// the linkage cannot be assembled at some prescribed input.
  double structural_error_rms = 0.0, structural_error_max = 0.0;
  Eigen::VectorXd phi_generated;      ///< radians, each within pi of the prescribed phi_i; empty if not assemblable
  int iterations = 0;                 ///< Gauss-Newton steps (0 for the design solution)
  double final_step_norm = 0.0;       ///< ||Delta k|| (with dial zeros ||Delta (k, alpha, beta)||) of the last step
  bool rounding_limited = false;      ///< stopped at rounding level above the tolerance (StructuralRefinement)
  std::optional<MotionCheck> check;   ///< Grashof type, transmission angle, branch defect (with lengths)
};

/// The result of synthesize().
struct SynthesisResult {
  SynthesisStatus status = SynthesisStatus::Success;
  std::string message;              ///< why it failed, when status != Success
  Eigen::Index positions = 0;       ///< m
  bool precision_point = false;     ///< exactly as many positions as unknowns: exact synthesis (3.3.3)
  bool dial_zeros_fitted = false;
  int branch = 1;                   ///< the assembly branch followed (+1 or -1, output_angle)
  Eigen::Index rank = 0;            ///< of W^(1/2) S at the design solution
  double condition_number = 0.0;    ///< of W^(1/2) S at the design solution
  double scaled_condition_number = 0.0;  ///< of W^(1/2) S with unit-norm columns (decides the rank)
  bool used_svd = false;            ///< S was rank-deficient: edited SVD
  Eigen::VectorXd psi, phi;         ///< prescribed absolute angles (radians) at the design dial zeros
  LinkageSolution design;           ///< minimizes the design error (section 3.4)
  LinkageSolution structural;       ///< minimizes the structural error (section 3.6); = design when not refined
  std::vector<Warning> warnings;

  bool ok() const { return status == SynthesisStatus::Success; }
};

/// Synthesizes a four-bar function generator from prescribed input/output angle changes
/// (radians) delta_psi, delta_phi (the motion order) with weights w (empty: all 1):
///  1. design error (section 3.4): k minimizing 1/2 d^T W d by Householder QR (edited SVD when
///     S is rank-deficient); with fit_dial_zeros, (k, alpha, beta) minimizing the design error of
///     eq. 3.7 by Gauss-Newton with step halving, from the start described in SynthesisOptions;
///  2. the assembly branch whose outputs follow the prescribed ones (nearest_branch);
///  3. structural error (section 3.6): Gauss-Newton from the design solution (eq. 3.18; with
///     fit_dial_zeros also over alpha and beta, where ds/dbeta = 1 and ds/dalpha = (df/dpsi) /
///     (df/dphi), from both the design fit and the grid start, keeping the better), unless there are exactly as many positions as unknowns (3, or 5 with dial zeros:
///     precision points, section 3.3.3, solved exactly by step 1) or refine is off;
///  4. the link lengths of each solution (eq. 3.4) and their check_motion.
///
/// Status NoRealLinkage when a solution has no real link lengths, NotAssemblable when the design
/// linkage cannot reach some prescribed input (so there is no structural error to refine),
/// Diverged when Gauss-Newton fails; the message says which and gives k. The design solution is
/// filled in whenever step 1 ran.
///
/// Preconditions: equal lengths, at least 3 positions (5 with fit_dial_zeros), finite angles,
/// weights empty or positive and finite, valid options (else std::invalid_argument).
/// Cost: O(m) per Gauss-Newton step; the dial-zero grid adds O(5184 m).
SynthesisResult synthesize(const Eigen::Ref<const Eigen::VectorXd>& delta_psi,
                           const Eigen::Ref<const Eigen::VectorXd>& delta_phi,
                           const Eigen::Ref<const Eigen::VectorXd>& weights, const SynthesisOptions& options = {});

}  // namespace spdfit::linkage
