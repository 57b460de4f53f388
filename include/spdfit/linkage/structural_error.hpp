// The structural error of a function generator and its minimization by Gauss-Newton (notes 002,
// section 3.6).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "spdfit/linkage/status.hpp"

namespace spdfit::linkage {

/// The generated output angles phi_gen,i (radians) of the linkage with parameters k at the inputs
/// psi on branch `branch` (+1 or -1; output_angle), each shifted by a multiple of 2 pi to lie
/// within pi of `near` (the prescribed outputs). Nothing when the linkage cannot be assembled at
/// some psi_i.
std::optional<Eigen::VectorXd> generated_outputs(const Eigen::Vector3d& k, const Eigen::Ref<const Eigen::VectorXd>& psi,
                                                 const Eigen::Ref<const Eigen::VectorXd>& near, int branch);

/// The structural error s_i = phi_pres,i - phi_gen,i (notes 3.6), in [-pi, pi]. Nothing when the
/// linkage cannot be assembled at some psi_i.
std::optional<Eigen::VectorXd> structural_error(const Eigen::Vector3d& k, const Eigen::Ref<const Eigen::VectorXd>& psi,
                                                const Eigen::Ref<const Eigen::VectorXd>& phi, int branch);

/// The assembly branch (+1 or -1) whose generated outputs follow the prescribed ones best (least
/// weighted sum of squared structural errors; +1 on a tie). Nothing when the linkage cannot be
/// assembled at every psi_i (then neither branch can: assembly depends on psi only).
std::optional<int> nearest_branch(const Eigen::Vector3d& k, const Eigen::Ref<const Eigen::VectorXd>& psi,
                                  const Eigen::Ref<const Eigen::VectorXd>& phi, const Eigen::Ref<const Eigen::VectorXd>& weights);

/// Options for the Gauss-Newton iteration.
#pragma GCC diagnostic push
// The deprecated field below must not warn in the copies the compiler writes for every user.
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
struct GaussNewtonOptions {
  /// Stop when ||Delta k|| < tolerance (notes 3.6.1: "stop when ||Delta k|| < epsilon"). The
  /// Freudenstein parameters of practical linkages are of order 1, so 1e-10 is about ten digits.
  double tolerance = 1e-10;
  int max_iterations = 100;
  /// Relative singular-value cut-off for each step's least-squares problem (nothing: max(m, n)
  /// eps, notes 3.8).
  std::optional<double> rank_tolerance;
  /// The old name of rank_tolerance (negative: the default), used when rank_tolerance is not set;
  /// removed in the next release.
  [[deprecated("use rank_tolerance")]] double threshold = -1.0;
};
#pragma GCC diagnostic pop

/// The outcome of a Gauss-Newton refinement.
struct StructuralRefinement {
  SynthesisStatus status = SynthesisStatus::Success;
  std::string message;             ///< why it failed, when status != Success
  Eigen::Vector3d k = Eigen::Vector3d::Zero();
  int iterations = 0;              ///< Gauss-Newton steps taken
  double step_norm = 0.0;          ///< ||Delta k|| of the last step computed
  /// Stopped with ||Delta k|| >= tolerance because the steps stopped shrinking at rounding level
  /// (an ill-conditioned D^-1 S amplifies rounding): k is as accurate as floating point allows.
  bool rounding_limited = false;
};

/// Minimizes zeta = 1/2 s^T W s over k from the start k0 (usually the design-error solution) by
/// Gauss-Newton (notes eq. 3.18): each step solves W^(1/2) D^-1 S Delta k = -W^(1/2) s in the
/// least-squares sense (Householder QR, edited SVD when rank-deficient), where
/// D = diag(df_i/dphi_gen,i) and S is the synthesis matrix at the generated angles, and stops
/// when ||Delta k|| < tolerance. The output stays on `branch` throughout. A step that would
/// raise zeta, leave the linkage unassemblable at a prescribed input, or give no real linkage
/// (eq. 3.4) is halved (up to 30 times; on well-behaved problems the full step is always taken,
/// which is the notes' iteration). Status Diverged, with a message, when no halving helps while
/// the step is still large, when the iteration limit is reached, or when k stops being finite.
///
/// Preconditions: as design_error_synthesis; k0 assemblable at every psi_i on `branch`, branch
/// +1 or -1 (else std::invalid_argument). Cost: O(m) per iteration.
StructuralRefinement refine_structural_error(const Eigen::Vector3d& k0, const Eigen::Ref<const Eigen::VectorXd>& psi,
                                             const Eigen::Ref<const Eigen::VectorXd>& phi,
                                             const Eigen::Ref<const Eigen::VectorXd>& weights, int branch,
                                             const GaussNewtonOptions& options = {});

}  // namespace spdfit::linkage
