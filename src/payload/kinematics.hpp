// Internal: a payload log's signals turned into what the wrench model needs, per sample and in the
// sensor frame S: the wrench w, the specific force s = a - R^T g, omega and alpha; with the checks
// of the orientation (quaternions normalized or refused, rotation matrices checked), the noise
// model's covariances and the rows chosen.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/payload/identify.hpp"

namespace spdfit::payload::detail {

/// Bad signals on valid options (a quaternion far from unit norm, a rotation that is not one, time
/// that does not increase): identify_file turns it into an io::DataError naming the file.
struct SignalError : InputError {
  explicit SignalError(const std::string& message, Code code = Code::DataValue) : InputError(message, code) {}
};

/// The samples in S, one column each (3 x m or 6 x m, so that a sample's values are contiguous).
struct Kinematics {
  Eigen::Matrix<double, 6, Eigen::Dynamic> wrench;
  Eigen::Matrix<double, 3, Eigen::Dynamic> specific_force, omega, alpha;
  bool moving = false;  ///< omega given: the inertia is in the model
  bool rotating = false;  ///< omega or alpha nonzero somewhere
  double sign = -1.0;   ///< -1 for WrenchSign::Load, +1 for Applied
  Eigen::Index distinct_orientations = 0;
  std::vector<Warning> warnings;

  Eigen::Index samples() const { return wrench.cols(); }
};

/// The noise model: Sigma_w (6 x 6) and Sigma_x = blockdiag(Sigma_s, Sigma_omega, Sigma_alpha)
/// (9 x 9); each empty when not known.
struct NoiseCovariances {
  Eigen::MatrixXd wrench, pose;
  std::string source;  ///< "std", "rest" or "" (none)
};

/// The kinematics of the signals' rows `rows` (all when empty), checked. Throws SignalError for bad
/// signals, OptionError for a request that does not fit them (an orientation missing or given
/// twice, frame base without a rotation, ...).
Kinematics kinematics(const PayloadSignals& signals, const IdentifyRequest& request,
                      const std::vector<Eigen::Index>& rows = {});

/// The noise model of the request: standard deviations, or the sample covariances of the rest rows
/// `rest` of `all` (the kinematics of every row), completed for derived alpha.
NoiseCovariances noise_covariances(const IdentifyRequest& request, const Kinematics& rest, bool alpha_derived,
                                   double time_step);

/// The rows of a selection "601:", "1:5000,7001:" (1-based inclusive; in `time`'s units when
/// given) among m rows, 0-based ascending, as fit's `rows` (io/row_selection.hpp): OptionError
/// naming `option` for bad syntax; SignalError for rows beyond the m or times that select none.
std::vector<Eigen::Index> select_rows(const std::string& spec, Eigen::Index m, const Eigen::VectorXd& time,
                                      const std::string& option);

/// Each sample's distinct gravity directions (to 1e-3 rad), counted up to `limit`.
Eigen::Index distinct_directions(const Eigen::Matrix<double, 3, Eigen::Dynamic>& g, Eigen::Index limit);

}  // namespace spdfit::payload::detail
