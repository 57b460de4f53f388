// Physically consistent least squares for any model linear in the inertial parameters of K rigid
// bodies (`spdfit physical regress`): a robot's joint torques tau = Y(q, qd, qdd) phi from the
// regressor Y that the user's code or pinocchio's computeJointTorqueRegressor produces, with each
// body's pseudo-inertia kept positive semidefinite, the base parameters, the combinations the data
// leave undetermined (or set by a prior), the KKT certificate and bootstrap uncertainty.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/physical/identifiability.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit::physical {

/// The order of each body's ten parameters in the regressor's columns: mass, first moment
/// m c (x, y, z), then the inertia about the body frame's origin (not the centre of mass) as
/// URDF lists it (xx, xy, xz, yy, yz, zz) or as pinocchio's Inertia::toDynamicParameters does
/// (xx, xy, yy, xz, yz, zz).
enum class ParamOrder { Urdf, Pinocchio };

/// "urdf" or "pinocchio".
std::string_view to_string(ParamOrder order);
std::optional<ParamOrder> parse_param_order(std::string_view name);

/// The parameter names of body k (1-based in the names: "m_1", "mc_x_1", "I_xx_1", ...) in `order`.
std::vector<std::string> body_parameter_names(int k, ParamOrder order);

/// What `regress` needs besides Y and tau. Messages name the fields in backticks.
struct RegressRequest {
  int bodies = 1;  ///< K: the regressor's first 10 K columns are the bodies' parameters
  ParamOrder param_order = ParamOrder::Urdf;
  /// Enforce each body's pseudo-inertia >= 0; false: ordinary least squares (for comparison).
  bool consistent = true;
  /// The covariance of the noise in one sample's outputs (d x d, symmetric positive definite):
  /// the rows of Y and tau come in samples of d consecutive rows (sample-major: all outputs of
  /// sample 1, then of sample 2, ...) and each sample's residual is weighted by its inverse. Empty:
  /// unweighted, samples of one row.
  Eigen::MatrixXd noise_cov;
  /// Prior bodies (for example from CAD): K bodies' mass, centre of mass and inertia about the
  /// centre of mass in each body's frame, each physically consistent with a positive definite
  /// pseudo-inertia. With a prior the criterion gains prior_weight times the sum of the
  /// log-determinant divergences of the bodies' pseudo-inertias from the prior's, which sets the
  /// parameters the data do not determine. Empty: none (those parameters are reported undetermined).
  std::vector<RigidBodyInertia> prior;
  /// The prior's weight w against the whitened squared residuals divided by the unconstrained fit's
  /// residual variance (a chi-square-like scale: w = 1 counts the prior like one sample's worth of
  /// information per body). A finite number > 0.
  double prior_weight = 1.0;
  /// Newton steps at most, an integer >= 1.
  int max_iterations = 500;
  /// The relative cut-off of the regressor's numerical rank (unit-norm columns); nothing: the
  /// default rule (spdfit/rank.hpp).
  std::optional<double> rank_tolerance;
  /// Bootstrap replicates over samples (0: none); percentile intervals at `confidence`.
  int bootstrap = 0;
  double confidence = 0.95;
  std::uint64_t seed = 1;
  unsigned threads = 0;  ///< for the bootstrap's replicates; 0: one per core
  /// Files of the command line's options (`noise_cov` and `prior`), read by regress_files.
  std::string noise_cov_path, prior_path;
  /// The command line's: the files of Y and tau (positional), JSON or the report, and where.
  std::string y_path, tau_path;
  OutputRequest output;

  /// True when usable; otherwise `error` says why, naming the field.
  bool is_valid(std::string* error = nullptr) const;
};

/// The options of a RegressRequest, in the order help lists them: bodies, param_order,
/// unconstrained, noise_cov (a file), prior (a file), prior_weight, max_iterations,
/// rank_tolerance, bootstrap, confidence, seed, threads.
const std::vector<OptionSpec<RegressRequest>>& regress_option_table();

/// One body of the estimate.
struct RegressBody {
  Eigen::Matrix<double, 10, 1> parameters;  ///< in the request's order; NaN where undetermined
  RigidBodyInertia inertia;   ///< mass, centre of mass, inertia about it (NaN where undetermined)
  double pseudo_inertia_min_eig = 0.0;  ///< lambda_min of J (kg m^2 scale; >= 0: consistent)
  bool physically_consistent = false;
  bool determined = true;     ///< every one of its ten parameters determined (or set by the prior)
};

/// Bootstrap uncertainty of the estimate: per parameter, and per base parameter.
struct RegressBootstrap {
  int replicates = 0, failed = 0;
  std::uint64_t seed = 1;
  double level = 0.95;
  Eigen::VectorXd parameter_se, parameter_lower, parameter_upper;
  Eigen::VectorXd base_se, base_lower, base_upper;
};

/// What regress returns.
struct RegressResult {
  Status status = Status::NotComputed;
  std::string message;
  int bodies = 0;
  ParamOrder param_order = ParamOrder::Urdf;
  bool consistent_requested = true;
  bool prior_used = false;
  Eigen::Index samples = 0, outputs = 1, rows = 0;
  std::vector<std::string> names;  ///< one per column of Y ("m_1", ..., "x_1" for extra columns)
  Eigen::VectorXd parameters;      ///< one per column of Y; NaN where undetermined (no prior)
  std::vector<RegressBody> body;
  Eigen::VectorXd extra;           ///< the parameters of the columns after the bodies'
  Identifiability identifiability;
  Eigen::VectorXd base_parameters; ///< identifiability.base times the estimate
  /// ||W^1/2 (Y phi - tau)||^2 at the estimate and at the unconstrained least-squares fit.
  double criterion = 0.0, criterion_unconstrained = 0.0;
  double residual_rms = 0.0;       ///< sqrt of the criterion / rows
  Certificate certificate;
  int iterations = 0;
  bool converged = false;
  bool physically_consistent = false;  ///< every body
  std::vector<Warning> warnings;
  std::optional<RegressBootstrap> bootstrap;

  bool ok() const { return status == Status::Success; }
};

/// The physically consistent least-squares fit of tau ~= Y phi:
///
///     min ||W^1/2 (Y phi - tau)||^2 (+ w sum_k D(J_k || J0_k))  over J_k(phi) >= 0, k = 1..K,
///
/// J_k the pseudo-inertia of body k (rigid_body.hpp), W the inverse noise covariance per sample,
/// D the log-determinant divergence from the prior J0_k (Lee, Wensing and Park 2020). Y is the
/// stacked regressor (rows = samples x outputs, columns = 10 K body parameters in
/// request.param_order, then any extra columns, unconstrained), tau the stacked outputs (a column).
/// Solved from the triangular factor of [W^1/2 Y, W^1/2 tau] by the shared barrier and face method
/// of physical identification (convex: the certificate's duality gap bounds the distance from the
/// global minimum). The base parameters by a column-pivoted QR of the regressor with unit-norm
/// columns.
///
/// Errors: std::invalid_argument (OptionError for the options, naming them) for an invalid
/// request, Y without 10 K columns, tau not one column of Y's rows, rows not a multiple of the
/// noise covariance's size, non-finite data. A failure of the optimizer on valid data is status
/// NumericalFailure with a message. Cost O(rows p^2) for the factor, O(p^3) per Newton step
/// (p = Y's columns); times bootstrap + 1.
RegressResult regress(const Eigen::MatrixXd& Y, const Eigen::MatrixXd& tau, const RegressRequest& request);

/// regress with Y and tau read from files (any format spdfit reads) and the request's noise
/// covariance and prior from theirs (noise_cov_path: a d x d matrix file; prior_path: JSON, a list
/// of K bodies {"mass", "center_of_mass", "inertia"} or {"bodies": [...]}). io::DataError naming
/// the file for bad files.
RegressResult regress_files(const std::string& y_path, const std::string& tau_path, RegressRequest request,
                            const io::ReadOptions& read = {});

/// `physical regress` as one workflow: the table's rules among the options given (OptionError,
/// Code::OptionConflict), then regress_files on request.y_path and request.tau_path.
void check_regress_request(const RegressRequest& request, const std::vector<std::string_view>& given);
RegressResult run_regress(const RegressRequest& request, const io::ReadOptions& read = {});

/// The result as JSON text: {"status", "bodies", "param_order", "consistent", "prior", "samples",
/// "outputs", "rows", "names", "parameters", "body" [{"mass", "center_of_mass", "inertia",
/// "parameters", "pseudo_inertia_min_eig", "physically_consistent", "determined"}], "extra",
/// "rank", "condition", "base_parameters" [{"combination", "value"}], "undetermined"
/// [{"parameters", "coefficients", "combination"}], "criterion", "criterion_unconstrained",
/// "residual_rms", "certificate" {"stationarity", "primal_min_eig", "dual_min_eig",
/// "complementarity", "duality_gap"}, "iterations", "converged", "physically_consistent",
/// "warnings", "error" (on failure); with a bootstrap "bootstrap" {"replicates", "failed", "seed",
/// "level", "parameters" {"standard_errors", "lower", "upper"}, "base_parameters" {same}}.
/// Non-finite numbers are null.
std::string to_json(const RegressResult& result);

/// The result for people: each body's mass properties, the base parameters, what is undetermined,
/// the certificate.
std::string report(const RegressResult& result);

}  // namespace spdfit::physical

namespace spdfit {

/// What physical::to_json wrote, read back (spdfit/render.hpp's from_json): every key it writes;
/// std::invalid_argument naming the class and the key for another document.
template <typename T>
T from_json(const std::string& text);
template <> physical::RegressResult from_json<physical::RegressResult>(const std::string& text);

}  // namespace spdfit
