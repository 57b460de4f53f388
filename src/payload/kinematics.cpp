#include "payload/kinematics.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "io/row_selection.hpp"
#include "pipeline/sentinels.hpp"
#include "spdfit/format.hpp"
#include "spdfit/io.hpp"

namespace spdfit::payload::detail {

namespace {

// A quaternion whose norm is off by more than kQuaternionWarn is normalized with a warning; by
// more than kQuaternionRefuse it is not a rotation (a column mix-up, a logging error).
constexpr double kQuaternionWarn = 1e-3;
constexpr double kQuaternionRefuse = 0.1;
// The same for a rotation matrix: ||R^T R - 1||_F.
constexpr double kRotationWarn = 1e-3;
constexpr double kRotationRefuse = 0.1;
// Gravity columns whose mean magnitude is off by more than this fraction of |g| are probably in
// other units (g instead of m/s^2).
constexpr double kGravityMagnitude = 0.05;
// Two gravity directions closer than this (rad) count as one orientation.
constexpr double kDistinctAngle = 1e-3;

std::string row_text(Eigen::Index i) { return "row " + std::to_string(i + 1); }

void need_columns(const Eigen::MatrixXd& M, Eigen::Index cols, Eigen::Index m, const char* option, const char* what) {
  if (M.size() == 0) return;
  if (M.cols() != cols || M.rows() != m) {
    throw InputError("`" + std::string(option) + "` must give " + std::to_string(cols) + " columns (" + what +
                      ") with the wrench's " + std::to_string(m) + " rows, not " + std::to_string(M.rows()) + " x " +
                      std::to_string(M.cols()), Code::DataShape, option);
  }
  if (!M.allFinite()) {
    Eigen::Index bad = 0;
    for (; bad < M.rows(); ++bad)
      if (!M.row(bad).allFinite()) break;
    throw SignalError(row_text(bad) + ": the " + std::string(what) + " (`" + option + "`) is not finite (NaN or Inf)");
  }
}

}  // namespace

Eigen::Index distinct_directions(const Eigen::Matrix<double, 3, Eigen::Dynamic>& g, Eigen::Index limit) {
  std::vector<Eigen::Vector3d> seen;
  const double cos_limit = std::cos(kDistinctAngle);
  for (Eigen::Index i = 0; i < g.cols() && static_cast<Eigen::Index>(seen.size()) < limit; ++i) {
    const double n = g.col(i).norm();
    if (!(n > 0.0)) continue;
    const Eigen::Vector3d u = g.col(i) / n;
    bool known = false;
    for (const Eigen::Vector3d& v : seen) {
      if (u.dot(v) > cos_limit) {
        known = true;
        break;
      }
    }
    if (!known) seen.push_back(u);
  }
  return static_cast<Eigen::Index>(seen.size());
}

std::vector<Eigen::Index> select_rows(const std::string& spec, Eigen::Index m, const Eigen::VectorXd& time,
                                      const std::string& option) {
  // fit's row selections (io/row_selection.hpp), so that `rows` and `rest_rows` mean here what they
  // mean there; a selection beyond the log is the log's error (SignalError: the file route names it).
  try {
    if (time.size() == m && m > 0) return io::detail::selected_times(spec, option, time, "the log");
    return io::detail::selected_rows(spec, option, static_cast<std::uint64_t>(std::max<Eigen::Index>(m, 0)), "the log");
  } catch (const io::DataError& e) {
    throw SignalError(e.problem(), e.code());
  }
}

Kinematics kinematics(const PayloadSignals& signals, const IdentifyRequest& request,
                      const std::vector<Eigen::Index>& rows) {
  const Eigen::Index all = signals.wrench.rows();
  if (signals.wrench.cols() != 6) {
    throw InputError("`wrench_cols` must give 6 columns (fx fy fz tx ty tz), not " +
                      std::to_string(signals.wrench.cols()), Code::DataShape, "wrench_cols");
  }
  if (all == 0) throw SignalError("the log has no rows");
  need_columns(signals.wrench, 6, all, "wrench_cols", "wrench");
  need_columns(signals.quaternion, 4, all, "quat_cols", "quaternion");
  need_columns(signals.rotation, 9, all, "rotation_cols", "rotation matrix");
  need_columns(signals.gravity, 3, all, "gravity_cols", "gravity in the sensor frame");
  need_columns(signals.accel, 3, all, "accel_cols", "acceleration");
  need_columns(signals.specific_force, 3, all, "specific_force_cols", "specific force");
  need_columns(signals.omega, 3, all, "omega_cols", "angular velocity");
  need_columns(signals.alpha, 3, all, "alpha_cols", "angular acceleration");
  if (signals.time.size() > 0 && signals.time.size() != all) {
    throw InputError("`time_col` must give one value per row (" + std::to_string(all) + "), not " +
                      std::to_string(signals.time.size()), Code::DataShape, "time_col");
  }
  if (signals.time.size() > 0 && !signals.time.allFinite()) throw SignalError("the time column (`time_col`) is not finite");
  for (Eigen::Index i = 0; i < signals.time.size(); ++i) {
    // A logger's code for an invalid reading (9.9e37): that row has no place in time ranges.
    if (std::abs(signals.time(i)) >= spdfit::detail::kSentinelMagnitude) {
      throw SignalError(row_text(i) + ": the time column (`time_col`) holds " + format_number(signals.time(i)) +
                        ", a logger's code for an invalid reading, not a time: delete that row from the log");
    }
  }

  const int orientations = (signals.quaternion.size() > 0) + (signals.rotation.size() > 0) + (signals.gravity.size() > 0);
  const bool specific = signals.specific_force.size() > 0;
  if (orientations > 1) {
    throw OptionError("give the orientation once: `quat_cols`, `rotation_cols` or `gravity_cols`", Code::OptionConflict);
  }
  if (specific && signals.accel.size() > 0) {
    throw OptionError("give `accel_cols` (the kinematic acceleration) or `specific_force_cols` (an IMU's reading, "
                      "gravity included), not both: gravity would be counted twice", Code::OptionConflict);
  }
  const bool has_rotation = signals.quaternion.size() > 0 || signals.rotation.size() > 0;
  if (request.quat_order == QuaternionOrder::Wxyz && signals.quaternion.size() == 0) {
    throw OptionError("`quat_order` applies to quaternions (`quat_cols`): the orientation is not given as one", Code::OptionNotApplicable);
  }
  if (orientations == 0 && !specific) {
    throw OptionError("the orientation is needed for gravity: give `quat_cols`, `rotation_cols` or `gravity_cols` "
                      "(or an IMU's `specific_force_cols`)", Code::OptionConflict);
  }
  if (specific && orientations > 0 && !(request.frame == WrenchFrame::Base && has_rotation)) {
    throw OptionError("`specific_force_cols` already holds gravity: the orientation (`quat_cols`, `rotation_cols`, "
                      "`gravity_cols`) is used only to rotate a wrench logged in base axes (`frame` base); leave it out", Code::OptionConflict);
  }
  if (request.frame == WrenchFrame::Base && !has_rotation) {
    throw OptionError("`frame` base needs the rotation to bring the wrench into the sensor's axes: give `quat_cols` "
                      "or `rotation_cols`", Code::OptionConflict);
  }
  if (signals.alpha.size() > 0 && signals.omega.size() == 0) {
    throw OptionError("`alpha_cols` needs `omega_cols` (the angular velocity) too", Code::OptionConflict);
  }
  if (signals.omega.size() > 0 && signals.accel.size() == 0 && !specific) {
    throw OptionError("`omega_cols` needs the linear acceleration too: `accel_cols` (kinematic) or "
                      "`specific_force_cols` (an IMU's)", Code::OptionConflict);
  }
  if (signals.omega.size() > 0 && signals.alpha.size() == 0 && signals.time.size() == 0) {
    throw OptionError("`omega_cols` without `alpha_cols` needs `time_col`: alpha is then omega's derivative by "
                      "central differences in time", Code::OptionConflict);
  }
  Kinematics out;
  out.sign = request.wrench_sign == WrenchSign::Load ? -1.0 : 1.0;
  out.moving = signals.omega.size() > 0;
  std::vector<Eigen::Index> index = rows;
  if (index.empty()) {
    index.resize(static_cast<std::size_t>(all));
    for (Eigen::Index i = 0; i < all; ++i) index[static_cast<std::size_t>(i)] = i;
  }
  const auto m = static_cast<Eigen::Index>(index.size());
  out.wrench.resize(6, m);
  out.specific_force.resize(3, m);
  out.omega.setZero(3, m);
  out.alpha.setZero(3, m);
  Eigen::Matrix<double, 3, Eigen::Dynamic> gravity_in_s(3, m);

  Eigen::Index normalized = 0, first_normalized = -1;
  double worst_norm = 0.0;
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::Index i = index[static_cast<std::size_t>(k)];
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (signals.quaternion.size() > 0) {
      const Eigen::Vector4d q = signals.quaternion.row(i).transpose();
      const double w = request.quat_order == QuaternionOrder::Xyzw ? q(3) : q(0);
      const Eigen::Vector3d v = request.quat_order == QuaternionOrder::Xyzw ? Eigen::Vector3d(q.head<3>())
                                                                            : Eigen::Vector3d(q.tail<3>());
      const double n = std::sqrt(w * w + v.squaredNorm());
      const double off = std::abs(n - 1.0);
      if (off > kQuaternionRefuse) {
        throw SignalError(row_text(i) + ": the quaternion (`quat_cols`, order " +
                          std::string(to_string(request.quat_order)) + ") has norm " + format_number(n) +
                          ", not 1: not a rotation (are the columns and `quat_order` right?)");
      }
      if (off > kQuaternionWarn) {
        ++normalized;
        if (first_normalized < 0) first_normalized = i;
        worst_norm = std::max(worst_norm, off);
      }
      R = Eigen::Quaterniond(w / n, v.x() / n, v.y() / n, v.z() / n).toRotationMatrix();
    } else if (signals.rotation.size() > 0) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R(r, c) = signals.rotation(i, 3 * r + c);
      const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
      if (off > kRotationRefuse || !(R.determinant() > 0.0)) {
        throw SignalError(row_text(i) + ": the rotation matrix (`rotation_cols`, row-major) is not a rotation (||R^T R - "
                          "1|| = " + format_number(off) + ", det " + format_number(R.determinant()) + ")");
      }
      if (off > kRotationWarn) {
        ++normalized;
        if (first_normalized < 0) first_normalized = i;
        worst_norm = std::max(worst_norm, off);
        // The nearest rotation (polar factor).
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
        R = svd.matrixU() * svd.matrixV().transpose();
      }
    }
    Eigen::Matrix<double, 6, 1> w = signals.wrench.row(i).transpose();
    if (request.frame == WrenchFrame::Base) {
      w.head<3>() = R.transpose() * w.head<3>();
      w.tail<3>() = R.transpose() * w.tail<3>();
    }
    out.wrench.col(k) = w;
    const Eigen::Vector3d g_s = signals.gravity.size() > 0 ? Eigen::Vector3d(signals.gravity.row(i).transpose())
                                                           : Eigen::Vector3d(R.transpose() * request.gravity);
    gravity_in_s.col(k) = g_s;
    if (specific) {
      out.specific_force.col(k) = signals.specific_force.row(i).transpose();
      // Without an orientation the specific force's direction stands for gravity's (at rest they agree).
      if (orientations == 0) gravity_in_s.col(k) = -out.specific_force.col(k);
    } else {
      const Eigen::Vector3d a = signals.accel.size() > 0 ? Eigen::Vector3d(signals.accel.row(i).transpose())
                                                         : Eigen::Vector3d::Zero();
      out.specific_force.col(k) = a - g_s;
    }
    if (out.moving) out.omega.col(k) = signals.omega.row(i).transpose();
    if (signals.alpha.size() > 0) out.alpha.col(k) = signals.alpha.row(i).transpose();
  }
  if (normalized > 0) {
    const bool quaternion = signals.quaternion.size() > 0;
    out.warnings.push_back(Warning(Code::PhysicalNotice, std::to_string(normalized) + (normalized == 1 ? " row's " : " rows' ") +
                           (quaternion ? "quaternion" : "rotation matrix") + " (first " + row_text(first_normalized) +
                           ", worst off by " + format_number(worst_norm) + ") " +
                           (quaternion ? "had a norm off 1 by more than 1e-3: normalized"
                                       : "was off orthonormal by more than 1e-3: replaced by the nearest rotation")));
  }
  if (signals.gravity.size() > 0 && !specific) {
    const double mean = gravity_in_s.colwise().norm().mean();
    const double expected = request.gravity.norm();
    if (std::abs(mean - expected) > kGravityMagnitude * expected) {
      out.warnings.push_back(Warning(Code::PhysicalNotice, "the gravity columns (`gravity_cols`) have a mean magnitude of " + format_number(mean) +
                             " m/s^2, not |g| = " + format_number(expected) +
                             " m/s^2: the mass comes out in their units (are they in g?)"));
    }
  }

  // alpha from omega: central differences in time (one-sided at the ends), over the whole log so
  // that a row selection does not change a row's alpha.
  if (out.moving && signals.alpha.size() == 0) {
    const Eigen::VectorXd& t = signals.time;
    for (Eigen::Index i = 1; i < all; ++i) {
      if (!(t(i) > t(i - 1))) {
        throw SignalError(row_text(i) + ": the time column (`time_col`) does not increase (" + format_number(t(i - 1)) +
                          " then " + format_number(t(i)) + "); alpha is omega's derivative in time");
      }
    }
    if (all < 3) throw SignalError("alpha from omega needs at least 3 rows");
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index i = index[static_cast<std::size_t>(k)];
      const Eigen::Index lo = i == 0 ? 0 : i - 1, hi = i == all - 1 ? all - 1 : i + 1;
      out.alpha.col(k) = (signals.omega.row(hi) - signals.omega.row(lo)).transpose() / (t(hi) - t(lo));
    }
    out.warnings.push_back(Warning(Code::PhysicalNotice, "alpha (the angular acceleration) is omega's derivative by central differences in time "
                           "(`time_col`): noise in omega is amplified by 1/(2 dt); give `alpha_cols` when the logger "
                           "has it"));
  }
  out.rotating = out.moving && (out.omega.cwiseAbs().maxCoeff() > 0.0 || out.alpha.cwiseAbs().maxCoeff() > 0.0);
  out.distinct_orientations = distinct_directions(gravity_in_s, 1000);
  return out;
}

NoiseCovariances noise_covariances(const IdentifyRequest& request, const Kinematics& rest, bool alpha_derived,
                                   double time_step) {
  NoiseCovariances out;
  const auto diagonal = [](const std::vector<double>& std, int n, const char* option) {
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
    if (std.empty()) return S;
    if (n == 6 && std.size() == 2) {
      for (int i = 0; i < 3; ++i) S(i, i) = std[0] * std[0];
      for (int i = 3; i < 6; ++i) S(i, i) = std[1] * std[1];
      return S;
    }
    if (std.size() != 1 && static_cast<int>(std.size()) != n) {
      throw OptionError("`" + std::string(option) + "` takes 1" + (n == 6 ? ", 2 (force, torque)" : std::string()) +
                        " or " + std::to_string(n) + " standard deviations, not " + std::to_string(std.size()));
    }
    for (int i = 0; i < n; ++i) {
      const double s = std.size() == 1 ? std[0] : std[static_cast<std::size_t>(i)];
      S(i, i) = s * s;
    }
    return S;
  };
  const bool stds = !request.noise_std_wrench.empty() || !request.noise_std_accel.empty() ||
                    !request.noise_std_omega.empty() || !request.noise_std_alpha.empty();
  if (rest.samples() > 0) {
    // The sample covariances about the rest rows' own means (divisor N - 1).
    const auto covariance = [](const Eigen::MatrixXd& X) {  // variables in rows
      const Eigen::MatrixXd centred = X.colwise() - X.rowwise().mean();
      return Eigen::MatrixXd(centred * centred.transpose() / static_cast<double>(std::max<Eigen::Index>(X.cols() - 1, 1)));
    };
    out.source = "rest";
    out.wrench = covariance(rest.wrench);
    out.pose = Eigen::MatrixXd::Zero(9, 9);
    out.pose.block<3, 3>(0, 0) = covariance(rest.specific_force);
    if (rest.moving) {
      out.pose.block<3, 3>(3, 3) = covariance(rest.omega);
      out.pose.block<3, 3>(6, 6) = alpha_derived ? Eigen::MatrixXd(out.pose.block<3, 3>(3, 3) / (2.0 * time_step * time_step))
                                                 : covariance(rest.alpha);
    }
  } else if (stds) {
    out.source = "std";
    out.wrench = diagonal(request.noise_std_wrench, 6, "noise_std_wrench");
    out.pose = Eigen::MatrixXd::Zero(9, 9);
    out.pose.block<3, 3>(0, 0) = diagonal(request.noise_std_accel, 3, "noise_std_accel");
    out.pose.block<3, 3>(3, 3) = diagonal(request.noise_std_omega, 3, "noise_std_omega");
    if (!request.noise_std_alpha.empty()) {
      out.pose.block<3, 3>(6, 6) = diagonal(request.noise_std_alpha, 3, "noise_std_alpha");
    } else if (alpha_derived && time_step > 0.0) {
      // Central differences: alpha_i = (omega_{i+1} - omega_{i-1}) / (2 dt), variance 2 s^2 / (2 dt)^2.
      out.pose.block<3, 3>(6, 6) = out.pose.block<3, 3>(3, 3) / (2.0 * time_step * time_step);
    }
    if (request.noise_std_wrench.empty()) out.wrench.resize(0, 0);
    if (out.pose.cwiseAbs().maxCoeff() == 0.0) out.pose.resize(0, 0);
  }
  return out;
}

}  // namespace spdfit::payload::detail
