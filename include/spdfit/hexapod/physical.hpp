// Physical identification of a hexapod's payload: its mass, centre of mass and inertia (and the
// struts' moving masses) from accelerations and forces, physically consistent, with a certificate
// of the local minimum found and bootstrap intervals (docs/hexapod.md, "Physical identification").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/outcome.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/rigid_body.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::hexapod {

/// Where the struts' moving masses M_s = diag(strut masses) come from.
enum class StrutMasses {
  Geometry,  ///< the geometry's strut_mass (known from the design), not estimated
  Common,    ///< one mass for all six struts, estimated
  Each,      ///< six masses, estimated
};

/// "geometry", "common" or "each".
std::string_view to_string(StrutMasses strut_masses);
std::optional<StrutMasses> parse_strut_masses(std::string_view name);

/// The criterion minimized over the parameters.
enum class PhysicalCriterion {
  /// The errors-in-variables criterion sum_i r_i^T (M Sigma_A M + Sigma_B)^-1 r_i, r_i the rows of
  /// A M - B: minus the log-likelihood (up to constants) of independent rows whose accelerations
  /// carry noise of covariance Sigma_A and forces Sigma_B. With Sigma_A = Sigma_B = 1 it is the
  /// equal-noise total least-squares criterion of spd-tls. Consistent as m grows.
  ErrorsInVariables,
  /// ||A M - B||_F^2: noise in the forces only; biased towards a lighter payload when the
  /// accelerations are noisy. Convex: the start of ErrorsInVariables.
  LeastSquares,
};

/// "eiv" or "ls".
std::string_view to_string(PhysicalCriterion criterion);
std::optional<PhysicalCriterion> parse_physical_criterion(std::string_view name);

/// Options of identify_physical. Messages name the fields in backticks.
struct PhysicalOptions {
  StrutMasses strut_masses = StrutMasses::Geometry;
  PhysicalCriterion criterion = PhysicalCriterion::ErrorsInVariables;
  /// Enforce physical consistency (the pseudo-inertia >= 0 and strut masses >= 0). False gives the
  /// unconstrained "grey-box" fit of the same model, for comparison: it may return a payload that
  /// cannot exist (a negative mass, principal moments that break the triangle inequality).
  bool consistent = true;
  /// Sigma_A and Sigma_B, the covariances of the noise in a row of A and of B (6 x 6, symmetric
  /// positive semidefinite, at least one of them positive definite; in the data's units squared).
  /// Empty means the identity: then the criterion is equal-noise TLS, whose implied noise ratio
  /// depends on the units of A and B (kg/m and g/mm data give different answers unless the
  /// covariances are given and converted with the data). Only their ratio matters.
  Eigen::MatrixXd noise_cov_a, noise_cov_b;
  /// Newton steps at most (all barrier stages together), an integer >= 1.
  int max_iterations = 500;
  /// The relative cut-off of A's numerical rank (spdfit/rank.hpp), a number in [0, 1); nothing
  /// means the default rule, as FitOptions::rank_tolerance.
  std::optional<double> rank_tolerance;
  /// Bootstrap replicates (0: none): multinomial resamples of the rows of [A B], each refitted with
  /// the same options; needs the rows (the overload taking A and B).
  int bootstrap = 0;
  double confidence = 0.95;  ///< of the bootstrap's percentile intervals, in (0, 1)
  std::uint64_t seed = 1;    ///< replicate r draws from a generator keyed by (seed, r)
  unsigned threads = 0;      ///< for the bootstrap's replicates; 0: one per core

  /// Refuse data whose implied payload mass (the unconstrained least-squares fit's, and the
  /// estimate's) is not positive or more than kPlausibleMassFactor from the geometry's: the
  /// geometry is in SI units, and such data are in others (forces in kN) or far from this payload.
  /// An InputError (Code::PhysicalData) naming the factor. False fits them as they are (option
  /// `no_plausibility_check`).
  bool plausibility_check = true;
  /// Subtract the rest rows' means (rest_mean_a, rest_mean_b) from A and B before fitting: data
  /// logged untared, a static load in the forces (option `offsets` rest).
  bool tare = false;
  /// Fit constant offsets with the payload (option `offsets` estimate): B ~= A M_p(theta) + 1 c^T,
  /// the data centred by their column means (the factor of [1 A B]); c is reported
  /// (PhysicalEstimate::offsets_c). For logs without a rest segment. Not with `tare`.
  bool intercept = false;
  /// A robust fit (option `robust`): the rows reweighted by their residual under the physical
  /// model, whitened by the noise covariances, as FitOptions::robust reweights them for the
  /// generic estimators (Huber from the plain physical fit, Tukey from least trimmed squares);
  /// each reweighting a physical fit of the weighted rows. With `bootstrap`, each resample's
  /// counts multiply the weights, reweighted from the estimate.
  RobustLoss robust = RobustLoss::None;
  /// The robust loss's constant (FitOptions::robust_tuning); nothing: 95% efficiency.
  std::optional<double> robust_tuning;
  /// The rest rows' means and their count, from a noise model made of rest rows (apply_fit_options
  /// copies them): for `tare`, and for the warning about data that look untared. Empty: none.
  Eigen::VectorXd rest_mean_a, rest_mean_b;
  std::uint64_t rest_rows = 0;

  /// True when usable; otherwise `error` says why, naming the field.
  bool is_valid(std::string* error = nullptr) const;
};

/// The first-order optimality (KKT) conditions of the local minimum found, for the problem
/// min f(theta) over P(theta) >= 0, s >= 0 (P the pseudo-inertia scaled to kg, s the estimated
/// strut masses, f the criterion). The multipliers are the gradient's parts Z = df/dP and
/// lambda = df/ds. Every number is made dimensionless by f0 (the data's own scale: the criterion
/// with all of B unexplained, sum_i b_i^T W^-1 b_i with the start's weight W; ||B||_F^2 for least
/// squares) and ||theta||: stationarity is the gradient along the face of the cone that P and
/// s lie on (zero at a KKT point), dual_min_eig the smallest eigenvalue of Z and entry of lambda
/// (>= 0 at a KKT point), complementarity <P, Z> + s . lambda (zero at a KKT point). The
/// criterion is not convex, so no certificate can prove a global minimum.
struct PhysicalCertificate {
  double stationarity = 0.0;
  double primal_min_eig = 0.0;  ///< min(lambda_min(P), s) in kg: >= 0 is physical consistency
  double dual_min_eig = 0.0;
  double complementarity = 0.0;
};

/// Which parameters the geometry lets M_p determine: the design of the linear map theta -> M_p(theta)
/// (21 entries of M_p from 10 payload parameters and 0, 1 or 6 strut masses, each in kg: the
/// centre of mass times the mass and the second moments divided by length_scale and its square).
struct PhysicalDesign {
  Eigen::Index parameters = 0;  ///< 10 + the strut masses estimated
  Eigen::Index rank = 0;        ///< of the 21 x parameters design
  double condition = 0.0;       ///< its sigma_max / sigma_min (inf when rank-deficient)
  double length_scale = 0.0;    ///< L, the RMS distance of the payload joints from {P}'s origin (m)
  /// A basis of the null space (parameters x (parameters - rank)): combinations of the parameters
  /// that leave M_p unchanged, in the order mass, 3 first moments m c / L, 6 second moments
  /// (xx, yy, zz, xy, xz, yz) / L^2, strut masses.
  Eigen::MatrixXd null_space;
  /// The confounded combination in words (empty when rank == parameters).
  std::string confounded;
};

/// The identifiability of the payload (and strut masses, per `strut_masses`) on `geometry`.
/// Throws std::invalid_argument unless geometry.is_valid(). Cost O(1) (a 21 x 16 SVD).
PhysicalDesign physical_design(const Geometry& geometry, StrutMasses strut_masses);

/// Bootstrap uncertainty of a group of values (a scalar, vector or matrix), entry by entry: the
/// replicates' standard deviation (divisor N - 1) and the percentile interval at the level.
struct EntryUncertainty {
  Eigen::MatrixXd standard_errors, lower, upper;
};

/// The bootstrap of identify_physical, entry by entry for each key of the estimate.
struct PhysicalBootstrap {
  int replicates = 0;
  int failed = 0;            ///< replicates without an estimate, left out
  std::uint64_t seed = 1;
  double level = 0.95;
  EntryUncertainty mass, center_of_mass, inertia, principal_moments, strut_mass, M_p;
  SpectrumUncertainty M_p_eigenvalues;    ///< with clusters, as identify's
  std::optional<SpectrumUncertainty> modes_hz;  ///< when the geometry's stiffnesses are all > 0
};

/// What identify_physical returns.
struct PhysicalEstimate {
  Status status = Status::NotComputed;
  std::string message;  ///< why it failed, when status != Success
  PhysicalCriterion criterion_kind = PhysicalCriterion::ErrorsInVariables;
  StrutMasses strut_masses = StrutMasses::Geometry;
  bool consistent_requested = true;  ///< PhysicalOptions::consistent

  RigidBodyInertia payload;       ///< mass (kg), centre of mass ({P}, m), inertia about it ({P} axes, kg m^2)
  PrincipalInertia principal;     ///< of payload.inertia: moments ascending, axes as columns
  Eigen::VectorXd strut_mass;     ///< 1 (common) or 6 (each; geometry: the geometry's, not estimated)
  Matrix6d M_p = Matrix6d::Zero();                  ///< M_p(theta), exactly symmetric
  Vector6d M_p_eigenvalues = Vector6d::Zero();      ///< ascending
  std::optional<Vector6d> modes_hz;                 ///< with the geometry's stiffnesses, when all > 0
  /// lambda_min of the pseudo-inertia about {P}'s origin scaled to kg (diag(1/L, 1/L, 1/L, 1) J
  /// diag(1/L, 1/L, 1/L, 1), L = design.length_scale): >= 0 exactly when the payload is physical.
  double pseudo_inertia_min_eig = 0.0;
  /// pseudo_inertia_min_eig and every strut mass >= 0, to the rounding of the pseudo-inertia's
  /// eigenvalues (64 eps of the largest): an estimate on the boundary is exactly rank-deficient,
  /// and its computed smallest eigenvalue is +-1e-15 relative.
  bool physically_consistent = false;
  PhysicalCertificate certificate;
  /// The convex least-squares start (ErrorsInVariables) or the estimate itself (LeastSquares), as
  /// psd-ls certifies its estimate: the KKT numbers of that convex problem, whose duality gap
  /// (relative to f0) bounds the distance of its criterion from the global minimum.
  PsdCertificate start_certificate;
  double criterion = 0.0;   ///< f at the estimate (the data's units)
  int iterations = 0;       ///< Newton steps
  bool converged = false;
  PhysicalDesign design;
  Eigen::Index m = 0;       ///< rows of the data
  Eigen::Index rank_a = 0;  ///< numerical rank of A
  std::vector<Warning> warnings;
  std::optional<PhysicalBootstrap> bootstrap;
  /// With PhysicalOptions::tare: the rest rows' means subtracted from A and from B (empty without).
  Eigen::VectorXd tare_a, tare_b;
  /// With PhysicalOptions::intercept: the offsets c = mean(B) - M_p^T mean(A) (6; the weighted
  /// means with `robust`), in B's units; empty without.
  Eigen::VectorXd offsets_c;
  /// With PhysicalOptions::robust: what the reweighting did to the rows.
  std::optional<RobustReport> robust;

  bool ok() const { return status == Status::Success; }
};

/// The payload's mass, centre of mass and inertia about it (and, with strut_masses common or
/// each, the struts' moving masses) from accelerations A and forces B (m x 6 each, one sample per
/// row, B ~= A M_p), with the geometry's Jacobian known:
///
///     M_p(theta) = J^-T R ^P M_x R^T J^-1 + diag(strut masses)     (thesis eq. 2.10/2.12),
///
/// ^P M_x as payload_mass_matrix(geometry, payload) (model.hpp): linear in the ten inertial
/// parameters. Minimizes options.criterion over them subject to physical consistency (the
/// pseudo-inertia pseudo_inertia(payload) >= 0, strut masses >= 0) with spdfit's own method: the
/// convex least-squares fit first (solved to a certified duality gap: start_certificate); then,
/// since the errors-in-variables criterion is not convex, two starts whose lower local minimum
/// wins: a primal barrier path from the least-squares fit (Newton steps with the exact Hessian on
/// the criterion plus mu (-log det P - sum log s), mu decreased to rounding level) and Newton's
/// method without constraints from the unconstrained least-squares fit; between barrier stages, and
/// from an unconstrained minimum outside the cone, a face solve (the criterion over P = L L^T of the
/// rank the iterate points to) that stops the path at a KKT point. Works from the triangular factor
/// of [A B] (the criterion depends on the data only through R^T R).
///
/// Errors: std::invalid_argument, naming the field or parameter, for invalid options or geometry,
/// A and B not m x 6 or not finite, a parameter that the geometry confounds (strut_masses common
/// or each where the design has a null space: the message names the combination), or data that
/// cannot identify a parameter (A of rank < 6 with a null direction reaching the parameters).
/// A failure of the optimizer on valid data is status NumericalFailure with a message.
/// Cost: O(m) for the factor, then O(1) per Newton step (6 x 6 matrices, at most 16 parameters);
/// times options.bootstrap + 1.
PhysicalEstimate identify_physical(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Geometry& geometry,
                                   const PhysicalOptions& options = {});

/// The same from the triangular factor of [A B] (n = d = 6), e.g. accumulated by streaming; no
/// bootstrap (options.bootstrap must be 0: the rows are gone).
PhysicalEstimate identify_physical(const TriangularFactor& factor, const Geometry& geometry,
                                   const PhysicalOptions& options = {});

/// The estimate as JSON text (the `physical` object of `spdfit hexapod identify --json`):
/// {"status", "mass", "center_of_mass" [3], "inertia" [3x3] (about the centre of mass, {P} axes),
/// "principal_moments", "principal_axes" (columns), "strut_mass" (a number for common, else 6),
/// "strut_masses" ("geometry", "common" or "each"), "M_p" [6x6], "M_p_eigenvalues", "modes_hz"
/// (when present), "pseudo_inertia_min_eig", "physically_consistent", "certificate"
/// {"stationarity", "primal_min_eig", "dual_min_eig", "complementarity"}, "start_certificate"
/// {"primal_min_eig", "dual_min_eig", "complementarity", "duality_gap"}, "criterion",
/// "criterion_kind" ("eiv" or "ls"), "consistent", "iterations", "converged", "design" {"parameters",
/// "rank", "condition", "length_scale", "confounded"}, "m", "rank_a", "warnings", "error" (on
/// failure); with a bootstrap "standard_errors" {mass, center_of_mass, inertia, principal_moments,
/// strut_mass, M_p} and "interval" {"level", "lower" {same keys}, "upper" {same keys}}, and
/// "bootstrap" {"replicates", "failed", "seed", "M_p_eigenvalues", "modes_hz"} (each {"estimate",
/// "standard_errors", "lower", "upper", "clusters", "failed"}). Non-finite numbers are null; the
/// others round-trip exactly.
std::string physical_json(const PhysicalEstimate& estimate);

}  // namespace spdfit::hexapod
