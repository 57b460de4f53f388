// A payload's mass, centre of mass and inertia, and the sensor's biases, from a wrist
// force/torque sensor's log over many poses (`spdfit payload identify`, docs/payload.md).
//
// In the sensor frame S, with R the rotation from S to the world (gravity g in the world), a the
// sensor origin's kinematic acceleration, omega and alpha its angular velocity and acceleration
// (all in S), s = a - R^T g the specific force, h = m c the first moment and I_S the inertia about
// S's origin, the wrench the sensor applies to the payload (torque about S's origin) is linear in
// phi = (m, h, I_S):
//
//     f = m s + alpha x h + omega x (omega x h),
//     tau = I_S alpha + omega x (I_S omega) + h x s.
//
// A sensor reports the load applied to it, w = -(f, tau) + b + noise (WrenchSign::Load; b the six
// biases), or the wrench applied to the payload, w = (f, tau) + b + noise (WrenchSign::Applied).
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

namespace spdfit::payload {

/// Which wrench the sensor's readings are.
enum class WrenchSign {
  Load,     ///< the load the payload applies to the sensor: w = -(f, tau) + b (what sensors report)
  Applied,  ///< the wrench applied to the payload: w = (f, tau) + b
};
/// Whose axes the wrench is logged in (the torque is about the sensor's origin either way).
enum class WrenchFrame {
  Sensor,  ///< the sensor frame S
  Base,    ///< the world (base) frame's axes: the logger rotated it by R
};
/// The order of a quaternion's four columns.
enum class QuaternionOrder {
  Xyzw,  ///< x, y, z, w (ROS's geometry_msgs/Quaternion, scipy's as_quat)
  Wxyz,  ///< w, x, y, z (Eigen's coeffs order aside, MATLAB's and most papers')
};
/// The criterion minimized.
enum class Criterion {
  LeastSquares,       ///< sum of the wrench residuals' squares (weighted by the wrench noise when given)
  ErrorsInVariables,  ///< sum_i r_i^T (J_i Sigma_x J_i^T + Sigma_w)^-1 r_i: noise in the pose signals too
};

std::string_view to_string(WrenchSign sign);
std::string_view to_string(WrenchFrame frame);
std::string_view to_string(QuaternionOrder order);
std::string_view to_string(Criterion criterion);
std::optional<WrenchSign> parse_wrench_sign(std::string_view name);
std::optional<WrenchFrame> parse_wrench_frame(std::string_view name);
std::optional<QuaternionOrder> parse_quaternion_order(std::string_view name);
std::optional<Criterion> parse_criterion(std::string_view name);

/// A log's signals as arrays, one row per sample (SI units). The orientation is one of
/// `quaternion` (m x 4, the rotation R from S to the world, in the request's quat_order),
/// `rotation` (m x 9, R row-major) or `gravity` (m x 3, R^T g: gravity in S, about -9.81 m/s^2
/// along S's axis that points up at rest); with `specific_force` (an IMU's reading of a - R^T g,
/// +9.81 m/s^2 upwards at rest) the orientation is needed only for a wrench logged in base axes.
/// The others are optional: `accel` (the kinematic acceleration a, m x 3), `omega` (m x 3),
/// `alpha` (m x 3; without it, alpha from omega by central differences over `time`).
struct PayloadSignals {
  Eigen::MatrixXd wrench;  ///< m x 6: fx fy fz (N), tx ty tz (N m)
  Eigen::MatrixXd quaternion, rotation, gravity;
  Eigen::MatrixXd accel, specific_force, omega, alpha;
  Eigen::VectorXd time;  ///< m, increasing (s)
};

/// Everything `payload identify` needs besides the signals: how to read them from a log, the
/// conventions, the criterion and its noise model, and the uncertainty. Messages name the fields
/// in backticks.
struct IdentifyRequest {
  /// The log (any format spdfit reads), for run_identify (identify_file's path).
  std::string log;
  // Columns of the log (io::ColumnSelection's syntax: header names and 1-based positions, ranges,
  // lists), for identify_file; the signals' arrays come from these.
  std::string wrench_cols, quat_cols, rotation_cols, gravity_cols;
  std::string accel_cols, specific_force_cols, omega_cols, alpha_cols;
  std::string time_col;
  /// Rows of the log fitted and rows recorded at rest (for the noise model): 1-based inclusive
  /// ranges and lists ("601:", "1:5000,7001:"); in the time column's units when time_col is given.
  std::string rows, rest_rows;
  io::ReadOptions read;

  WrenchSign wrench_sign = WrenchSign::Load;
  WrenchFrame frame = WrenchFrame::Sensor;
  QuaternionOrder quat_order = QuaternionOrder::Xyzw;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.80665);  ///< in the world frame (m/s^2)
  Criterion criterion = Criterion::LeastSquares;
  /// Physical consistency: the pseudo-inertia >= 0 (moving poses), m >= 0 (static poses). False:
  /// the unconstrained fit, for comparison.
  bool consistent = true;
  /// Standard deviations of the noise: the wrench's (1: all six, 2: force and torque, 6: each
  /// axis), the specific force's or acceleration's, omega's and alpha's (1 or 3 each). Empty: not
  /// given. The wrench's weights least squares; errors-in-variables needs the wrench's and at least
  /// one pose signal's (or rest_rows).
  std::vector<double> noise_std_wrench, noise_std_accel, noise_std_omega, noise_std_alpha;
  /// Newton steps at most.
  int max_iterations = 500;
  std::optional<double> rank_tolerance;
  /// A robust fit (an M-estimator, as fit's `robust`): samples reweighted by their residual
  /// wrench, whitened by the criterion's covariance (the wrench noise's, or each axis' robust
  /// scale without one; errors in variables: its per-sample covariance), each reweighting the
  /// criterion's fit of the weighted samples. Huber re-estimates the scale each time; Tukey starts
  /// from Huber's fit and scale. `robust_tuning`: the loss's constant (default: 95 % efficiency
  /// at Gaussian noise for a 6-axis residual).
  RobustLoss robust = RobustLoss::None;
  std::optional<double> robust_tuning;
  int bootstrap = 0;
  double confidence = 0.95;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  /// A URDF <link> of the payload: its name (`urdf` is the command line's file).
  std::string urdf, link_name = "payload";
  int precision = 9;
  OutputRequest output;  ///< the command line's: JSON or the report, and where

  /// True when usable (the options' values and combinations); otherwise `error` says why, naming
  /// the fields.
  bool is_valid(std::string* error = nullptr) const;
};

/// The options of an IdentifyRequest, in the order help lists them: the log (positional), the
/// columns, the conventions, the criterion and its noise, the solver's and the bootstrap's, the
/// URDF export, and the command line's json and output.
const std::vector<OptionSpec<IdentifyRequest>>& identify_option_table();

/// Checks the options given (`given`: library names) against the table's rules (each option's
/// `needs` and `excludes`). Throws OptionError (Code::OptionConflict). The rules that depend on
/// the signals given (an orientation once, eiv's noise model, ...) are identify's.
void check_identify_request(const IdentifyRequest& request, const std::vector<std::string_view>& given);

/// A parameter group's bootstrap uncertainty, entry by entry.
struct Interval {
  Eigen::MatrixXd standard_errors, lower, upper;
};

/// What identify returns.
struct PayloadEstimate {
  Status status = Status::NotComputed;
  std::string message;
  bool moving = false;  ///< the model has the inertia (omega given): 16 parameters, else 10
  Criterion criterion = Criterion::LeastSquares;
  bool consistent_requested = true;
  WrenchSign wrench_sign = WrenchSign::Load;
  WrenchFrame frame = WrenchFrame::Sensor;
  Eigen::Index samples = 0;
  std::vector<std::string> names;  ///< the parameters: m, mc_x, ..., I_xx, ..., b_fx, ..., b_tz
  Eigen::VectorXd parameters;      ///< phi and the biases; NaN where undetermined
  Eigen::VectorXd standard_errors; ///< of `parameters` (the sandwich estimate), NaN where undetermined
  double mass = 0.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();  ///< in S (m)
  /// About the centre of mass, in S's axes (kg m^2): NaN for static poses (not determined).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d inertia_origin = Eigen::Matrix3d::Zero();  ///< I_S, about S's origin
  PrincipalInertia principal;
  Eigen::Vector3d force_bias = Eigen::Vector3d::Zero(), torque_bias = Eigen::Vector3d::Zero();
  /// Standard errors (delta method from the parameters' covariance): mass, centre of mass,
  /// inertia about the centre of mass, principal moments, biases.
  double mass_se = 0.0;
  Eigen::Vector3d center_of_mass_se = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_se = Eigen::Matrix3d::Zero();
  Eigen::Vector3d principal_moments_se = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_bias_se = Eigen::Vector3d::Zero(), torque_bias_se = Eigen::Vector3d::Zero();
  /// The residual RMS per axis (N, N m) and the residuals themselves (samples x 6).
  Eigen::Matrix<double, 6, 1> residual_rms = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::MatrixXd residuals;
  physical::Identifiability identifiability;  ///< of the regressor: rank, condition, undetermined
  /// The unconstrained fit's mass and its standard error (how far the constraint moved it).
  double unconstrained_mass = 0.0, unconstrained_mass_se = 0.0;
  double criterion_value = 0.0;  ///< at the estimate (the data's units)
  double pseudo_inertia_min_eig = 0.0;  ///< moving: lambda_min of the scaled pseudo-inertia (kg); static: m
  bool physically_consistent = false;
  bool constraint_active = false;  ///< the estimate lies on the boundary of consistency
  physical::Certificate certificate;
  int iterations = 0;
  bool converged = true;
  /// The distinct gravity directions in S among the samples (to 1e-3 rad), at most 1000 counted.
  Eigen::Index distinct_orientations = 0;
  std::vector<Warning> warnings;
  /// With a bootstrap: mass, center_of_mass, inertia, principal_moments, force_bias, torque_bias.
  struct Bootstrap {
    int replicates = 0, failed = 0;
    std::uint64_t seed = 1;
    double level = 0.95;
    Interval mass, center_of_mass, inertia, principal_moments, force_bias, torque_bias;
  };
  std::optional<Bootstrap> bootstrap;
  /// With IdentifyRequest::robust: the loss, its constant, the scale, the samples down-weighted
  /// below 0.5 (numbered as the log's data rows), the reweightings. The estimate and its standard
  /// errors are those of the last weighted fit.
  std::optional<RobustReport> robust;

  bool ok() const { return status == Status::Success; }
};

/// Identifies the payload from the signals (request's column and row fields are not used):
/// least squares (the triangular factor of the whitened regressor; static poses under m >= 0 by
/// the one active set, moving poses over the pseudo-inertia cone by the shared barrier and face
/// method of physical identification, physical/regress.hpp) or errors-in-variables (Newton's
/// method on the criterion with its exact Hessian, from the least-squares fit; over the cone from
/// two starts as hexapod identify --physical). Standard errors by the sandwich (heteroskedasticity-
/// robust) estimate of the parameters' covariance; bootstrap over samples when asked.
///
/// Errors: OptionError for an invalid request or one that does not fit the signals (naming the
/// option: eiv without a noise model, --frame base without a rotation, ...); io::DataError-free
/// std::invalid_argument for bad signals (wrong column counts, NaN, a quaternion more than 0.1 from
/// unit norm, a rotation matrix that is not one), naming the row; a mass significantly negative
/// (beyond 4 standard errors) in the unconstrained fit is std::invalid_argument naming
/// `wrench_sign`. A failure of the optimizer on valid data is status NumericalFailure.
/// Cost O(m p^2) (p = 10 or 16) for least squares; O(m p^2) per Newton step for errors in variables.
PayloadEstimate identify(const PayloadSignals& signals, const IdentifyRequest& request);

/// identify on the columns of one log (any format spdfit reads) that the request selects. Column
/// selections that do not fit the file are io::ColumnSelectionError (usage); bad data io::DataError
/// naming the file and the row.
PayloadEstimate identify_file(const std::string& path, const IdentifyRequest& request);

/// `payload identify` as one workflow: identify_file on request.log.
PayloadEstimate run_identify(const IdentifyRequest& request);

/// The payload as a URDF <link> (urdf_link, inertia_repair.hpp) named request.link_name, to
/// request.precision significant digits: OptionError (naming `urdf`) for static poses, which do
/// not determine the inertia; std::invalid_argument when the estimate's mass is not positive or a
/// value is undetermined.
std::string urdf_text(const PayloadEstimate& estimate, const IdentifyRequest& request);

/// The estimate as JSON text: {"status", "model" ("static" or "moving"), "criterion", "consistent",
/// "wrench_sign", "frame", "samples", "mass", "center_of_mass", "inertia" (about the centre of
/// mass, null for static poses), "inertia_origin", "principal_moments", "principal_axes",
/// "force_bias", "torque_bias", "standard_errors" {"mass", "center_of_mass", "inertia",
/// "principal_moments", "force_bias", "torque_bias"}, "names", "parameters",
/// "parameter_standard_errors", "residual_rms" [6], "condition", "rank", "undetermined"
/// [{"parameters", "coefficients", "combination"}], "unconstrained_mass", "criterion_value",
/// "pseudo_inertia_min_eig", "physically_consistent", "constraint_active", "certificate",
/// "iterations", "converged", "distinct_orientations", "warnings", "error" (on failure); with a
/// bootstrap "bootstrap" {"replicates", "failed", "seed", "level"} and "interval" {"lower",
/// "upper"} and "bootstrap_standard_errors", each {the keys of "standard_errors"}. Non-finite
/// numbers are null.
std::string to_json(const PayloadEstimate& estimate);

/// The estimate for people: mass, centre of mass and inertia with standard errors, biases,
/// residual RMS per axis, what the poses do not determine, the certificate.
std::string report(const PayloadEstimate& estimate);

}  // namespace spdfit::payload

namespace spdfit {

/// What payload::to_json wrote, read back (spdfit/render.hpp's from_json): every key it writes;
/// std::invalid_argument naming the class and the key for another document.
template <typename T>
T from_json(const std::string& text);
template <> payload::PayloadEstimate from_json<payload::PayloadEstimate>(const std::string& text);

}  // namespace spdfit
