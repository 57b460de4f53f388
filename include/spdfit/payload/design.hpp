// Choosing the poses of a payload calibration (`spdfit payload design`): K of the candidate
// orientations that maximize the information of the static regressor about the mass, the first
// moment and the sensor's biases.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/payload/identify.hpp"

namespace spdfit::payload {

/// The optimality criterion: D maximizes log det F (F the Fisher information of the ten static
/// parameters: invariant under their units), E its smallest eigenvalue and A minimizes tr F^-1, both
/// of F with unit diagonal over the whole pool (so that the parameters' units do not decide).
enum class DesignCriterion { D, E, A };
std::string_view to_string(DesignCriterion criterion);
std::optional<DesignCriterion> parse_design_criterion(std::string_view name);

/// What `payload design` needs besides the candidates.
struct DesignRequest {
  std::string candidates;  ///< the candidates' file (one pose per row), for run_design
  int poses = 6;  ///< K, the poses chosen (>= 1; the ten parameters need 3 distinct gravity directions)
  DesignCriterion criterion = DesignCriterion::D;
  /// The candidates' orientation columns, as payload identify takes them (one of the three).
  std::string quat_cols, rotation_cols, gravity_cols;
  QuaternionOrder quat_order = QuaternionOrder::Xyzw;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.80665);
  /// The noise of a pose's wrench (1, 2: force and torque, or 6 standard deviations): the predicted
  /// standard errors are in the parameters' units with it.
  std::vector<double> noise_std_wrench = {1.0};
  /// Samples averaged at each pose: the information is that many times one sample's.
  int samples_per_pose = 1;
  /// A nominal payload for the predicted standard error of its centre of mass (c = h / m).
  double mass = 1.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  /// Random K-pose choices from the same pool to compare with (0: none), drawn with `seed`.
  int random = 1000;
  std::uint64_t seed = 1;
  io::ReadOptions read;
  /// The command line's: JSON or the report on standard output; `output` is the file the chosen
  /// rows are written to.
  OutputRequest output;

  bool is_valid(std::string* error = nullptr) const;
};

/// The options of a DesignRequest, in the order help lists them.
const std::vector<OptionSpec<DesignRequest>>& design_option_table();

/// A design's numbers.
struct DesignScore {
  double log_det = 0.0;        ///< log det F (-inf when singular)
  double condition = 0.0;      ///< of the regressor with unit-norm columns over the pool: sqrt(cond F_scaled)
  double se_mass = 0.0;        ///< predicted standard error of m (kg)
  Eigen::Vector3d se_center_of_mass = Eigen::Vector3d::Zero();  ///< of c (m), at the nominal payload
  double se_center_of_mass_norm = 0.0;  ///< sqrt of the trace of c's covariance (m)
};

/// What design returns.
struct DesignResult {
  DesignCriterion criterion = DesignCriterion::D;
  int poses = 0;
  Eigen::Index candidates = 0;
  std::vector<Eigen::Index> chosen;  ///< 0-based candidate indices, ascending
  DesignScore score;
  /// Over the random choices: each score's 10th, 50th and 90th percentiles (by the criterion's
  /// direction: for log det the 90th is the better), and the fraction of random choices the chosen
  /// design beats (or equals) on the standard error of m.
  int random = 0;
  Eigen::Vector3d random_log_det = Eigen::Vector3d::Zero(), random_se_mass = Eigen::Vector3d::Zero(),
                  random_se_center_of_mass = Eigen::Vector3d::Zero(), random_condition = Eigen::Vector3d::Zero();
  double beats_random = 0.0;
  Eigen::Index distinct_candidates = 0;  ///< distinct gravity directions in the pool
  std::vector<Warning> warnings;
  /// From design_file: the chosen rows of the candidates' file, every column, and its header.
  Eigen::MatrixXd chosen_rows;
  std::vector<std::string> column_names;
};

/// Chooses request.poses of the candidate orientations (gravity in the sensor frame, one per
/// column of `gravity_in_sensor`, 3 x n) by the criterion: greedy additions then Fedorov exchanges
/// (each chosen pose swapped for the candidate that improves the criterion most, until none does).
/// A pose may not be chosen twice. Cost O((n K + exchanges n K) p^3), p = 10.
/// std::invalid_argument (OptionError) for an invalid request or fewer candidates than poses.
DesignResult design(const Eigen::Matrix<double, 3, Eigen::Dynamic>& gravity_in_sensor, const DesignRequest& request);

/// design on candidates given as payload identify's signals (one of quaternion, rotation or gravity;
/// the wrench is not needed), converted with the request's quat_order and gravity.
DesignResult design(const PayloadSignals& candidates, const DesignRequest& request);

/// design on the candidates' orientation columns of a file (as payload identify reads a log).
DesignResult design_file(const std::string& path, const DesignRequest& request);

/// `payload design` as one workflow: the table's rules among the options given (OptionError,
/// Code::OptionConflict), then design_file on request.candidates.
void check_design_request(const DesignRequest& request, const std::vector<std::string_view>& given);
DesignResult run_design(const DesignRequest& request);

/// The chosen rows as CSV text (design_file's chosen_rows, with the file's header when it had one),
/// values that read back exactly: the poses to drive the robot to.
std::string chosen_rows_csv(const DesignResult& result);

/// The result as JSON text: {"criterion", "poses", "candidates", "chosen" (1-based), "log_det",
/// "condition", "se_mass", "se_center_of_mass", "se_center_of_mass_norm", "random" {"choices",
/// "log_det", "se_mass", "se_center_of_mass_norm", "condition" (each [p10, p50, p90]),
/// "beats"}, "distinct_candidates", "warnings"}.
std::string to_json(const DesignResult& result);
std::string report(const DesignResult& result);

}  // namespace spdfit::payload

namespace spdfit {

/// What payload::to_json wrote, read back (spdfit/render.hpp's from_json): every key it writes;
/// std::invalid_argument naming the class and the key for another document.
template <typename T>
T from_json(const std::string& text);
template <> payload::DesignResult from_json<payload::DesignResult>(const std::string& text);

}  // namespace spdfit
