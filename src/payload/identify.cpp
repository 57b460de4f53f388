// `payload identify` as a library workflow (payload/identify.hpp): the signals' kinematics and
// noise model, the fit (fit.cpp), the mass properties with their standard errors, the bootstrap.
#include "spdfit/payload/identify.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/parallel.hpp"
#include "payload/fit.hpp"
#include "payload/kinematics.hpp"
#include "physical/cone.hpp"
#include "physical/replicates.hpp"
#include "robust/m_estimator.hpp"
#include "spdfit/format.hpp"
#include "spdfit/inertia_repair.hpp"

namespace spdfit::payload {

namespace {

using detail::Fit;
using detail::Kinematics;
using detail::SignalError;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
// An unconstrained mass more than this many standard errors below zero is not noise: the readings
// have the other sign convention.
constexpr double kWrongSignSigmas = 4.0;

// The mass properties from phi (NaN where a parameter they need is undetermined), with the
// Jacobian of [m, c (3), I_c (9, column-major), principal moments (3), b_f (3), b_tau (3)] in phi.
struct Derived {
  double mass = kNan;
  Eigen::Vector3d c = Eigen::Vector3d::Constant(kNan);
  Eigen::Matrix3d I_c = Eigen::Matrix3d::Constant(kNan), I_o = Eigen::Matrix3d::Constant(kNan);
  PrincipalInertia principal;
  Eigen::Vector3d b_f, b_t;
  Eigen::MatrixXd D;  // 22 x p

  Eigen::VectorXd values() const {
    Eigen::VectorXd v(22);
    v << mass, c, I_c.reshaped(), principal.moments, b_f, b_t;
    return v;
  }
};

Eigen::Matrix3d symmetric_entry(int j) {
  static const int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(pairs[j][0], pairs[j][1]) = 1.0;
  E(pairs[j][1], pairs[j][0]) = 1.0;
  return E;
}

Derived derive(const Eigen::VectorXd& phi, bool moving) {
  Derived d;
  const int p = static_cast<int>(phi.size()), q = moving ? 10 : 4;
  d.D = Eigen::MatrixXd::Zero(22, p);
  d.principal.moments.setConstant(kNan);
  d.principal.axes.setConstant(kNan);
  d.b_f = phi.segment<3>(q);
  d.b_t = phi.segment<3>(q + 3);
  for (int i = 0; i < 6; ++i) d.D(16 + i, q + i) = 1.0;
  const double m = phi(0);
  const Eigen::Vector3d h = phi.segment<3>(1);
  d.mass = m;
  d.D(0, 0) = 1.0;
  if (!(std::abs(m) > 0.0) || !std::isfinite(m)) return d;
  d.c = h / m;
  for (int j = 0; j < 3; ++j) {
    d.D(1 + j, 0) = -h(j) / (m * m);
    d.D(1 + j, 1 + j) = 1.0 / m;
  }
  if (!moving) return d;
  const Eigen::Matrix3d I_o = physical::detail::inertia_of_urdf(phi);
  d.I_o = I_o;
  // I_c = I_o + (h h^T - |h|^2 1) / m.
  const Eigen::Matrix3d shift = (h * h.transpose() - h.squaredNorm() * Eigen::Matrix3d::Identity()) / m;
  d.I_c = I_o + shift;
  std::vector<Eigen::Matrix3d> dI(static_cast<std::size_t>(p), Eigen::Matrix3d::Zero());
  dI[0] = -shift / m;
  for (int l = 0; l < 3; ++l) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(l);
    dI[static_cast<std::size_t>(1 + l)] =
        (e * h.transpose() + h * e.transpose() - 2.0 * h(l) * Eigen::Matrix3d::Identity()) / m;
  }
  for (int j = 0; j < 6; ++j) dI[static_cast<std::size_t>(4 + j)] = symmetric_entry(j);
  for (int a = 0; a < p; ++a) d.D.block(4, a, 9, 1) = dI[static_cast<std::size_t>(a)].reshaped();
  if (d.I_c.allFinite()) {
    d.principal = principal_inertia(d.I_c);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = d.principal.axes.col(k);
      for (int a = 0; a < p; ++a) d.D(13 + k, a) = v.dot(dI[static_cast<std::size_t>(a)] * v);
    }
  }
  return d;
}

// Whether every parameter output i depends on (its row of D) is determined.
bool depends_on_determined(const Eigen::MatrixXd& D, Eigen::Index i, const std::vector<bool>& determined) {
  for (Eigen::Index a = 0; a < D.cols(); ++a)
    if (D(i, a) != 0.0 && !determined[static_cast<std::size_t>(a)]) return false;
  return true;
}

double median_step(const Eigen::VectorXd& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> steps;
  for (Eigen::Index i = 1; i < t.size(); ++i) steps.push_back(t(i) - t(i - 1));
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

}  // namespace

std::string_view to_string(WrenchSign sign) { return sign == WrenchSign::Applied ? "applied" : "load"; }
std::string_view to_string(WrenchFrame frame) { return frame == WrenchFrame::Base ? "base" : "sensor"; }
std::string_view to_string(QuaternionOrder order) { return order == QuaternionOrder::Wxyz ? "wxyz" : "xyzw"; }
std::string_view to_string(Criterion criterion) {
  return criterion == Criterion::ErrorsInVariables ? "eiv" : "ls";
}
std::optional<WrenchSign> parse_wrench_sign(std::string_view name) {
  if (name == "load") return WrenchSign::Load;
  if (name == "applied") return WrenchSign::Applied;
  return std::nullopt;
}
std::optional<WrenchFrame> parse_wrench_frame(std::string_view name) {
  if (name == "sensor") return WrenchFrame::Sensor;
  if (name == "base") return WrenchFrame::Base;
  return std::nullopt;
}
std::optional<QuaternionOrder> parse_quaternion_order(std::string_view name) {
  if (name == "xyzw") return QuaternionOrder::Xyzw;
  if (name == "wxyz") return QuaternionOrder::Wxyz;
  return std::nullopt;
}
std::optional<Criterion> parse_criterion(std::string_view name) {
  if (name == "ls") return Criterion::LeastSquares;
  if (name == "eiv") return Criterion::ErrorsInVariables;
  return std::nullopt;
}

PayloadEstimate identify(const PayloadSignals& signals, const IdentifyRequest& request) {
  std::string error;
  if (!request.is_valid(&error)) throw OptionError(error);
  const Eigen::Index all = signals.wrench.rows();
  const std::vector<Eigen::Index> rows =
      request.rows.empty() ? std::vector<Eigen::Index>{} : detail::select_rows(request.rows, all, signals.time, "rows");
  Kinematics kin = detail::kinematics(signals, request, rows);
  Kinematics rest;
  if (!request.rest_rows.empty()) {
    rest = detail::kinematics(signals, request, detail::select_rows(request.rest_rows, all, signals.time, "rest_rows"));
    if (rest.samples() < 2) throw OptionError("`rest_rows` must select at least 2 rows for a covariance", Code::OptionValue);
  }
  const bool alpha_derived = kin.moving && signals.alpha.size() == 0;
  const detail::NoiseCovariances noise =
      detail::noise_covariances(request, rest, alpha_derived, median_step(signals.time));
  if (request.criterion == Criterion::ErrorsInVariables) {
    if (noise.wrench.size() == 0 || noise.pose.size() == 0 || noise.pose.cwiseAbs().maxCoeff() == 0.0) {
      throw OptionError("`criterion` eiv weighs the noise in the pose signals against the wrench's: give "
                        "`noise_std_wrench` and the pose signals' (`noise_std_accel`, `noise_std_omega`, "
                        "`noise_std_alpha`), or `rest_rows`", Code::OptionConflict);
    }
  }

  std::optional<detail::RobustPayloadFit> robust;
  if (request.robust != RobustLoss::None) robust = detail::robust_fit_payload(kin, request, noise, {}, true);
  const Fit fit = robust ? robust->fit : detail::fit_payload(kin, request, noise, {}, true);
  PayloadEstimate out;
  out.moving = kin.moving;
  out.criterion = request.criterion;
  out.consistent_requested = request.consistent;
  out.wrench_sign = request.wrench_sign;
  out.frame = request.frame;
  out.samples = kin.samples();
  out.names = fit.layout.names();
  out.identifiability = fit.identifiability;
  out.distinct_orientations = kin.distinct_orientations;
  out.warnings = kin.warnings;
  const std::vector<bool>& determined = fit.identifiability.determined;

  // A significantly negative unconstrained mass: the readings' sign, never clipped silently.
  out.unconstrained_mass = determined[0] ? fit.phi_ls(0) : kNan;
  out.unconstrained_mass_se = determined[0] ? fit.mass_ls_se : kNan;
  if (determined[0] && fit.phi_ls(0) < -kWrongSignSigmas * fit.mass_ls_se) {
    const WrenchSign other = request.wrench_sign == WrenchSign::Load ? WrenchSign::Applied : WrenchSign::Load;
    throw SignalError("the unconstrained fit's mass is " + format_number(fit.phi_ls(0)) + " kg (standard error " +
                      format_number(fit.mass_ls_se) + " kg): significantly negative, so the readings have the other "
                      "sign convention than `wrench_sign` " + std::string(to_string(request.wrench_sign)) +
                      " says: try `wrench_sign` " + std::string(to_string(other)) +
                      " (or the gravity's direction, `gravity`, or the orientation's convention is wrong)", Code::PhysicalData);
  }

  out.status = Status::Success;
  out.iterations = fit.iterations;
  out.converged = fit.converged;
  out.criterion_value = fit.criterion;
  out.certificate = fit.certificate;
  if (!request.consistent) out.certificate = {kNan, kNan, kNan, kNan, kNan};
  out.constraint_active = fit.active;
  out.pseudo_inertia_min_eig = fit.pseudo_min;
  out.physically_consistent = fit.pseudo_min >= -64.0 * std::numeric_limits<double>::epsilon() * std::abs(fit.phi(0));

  const int p = static_cast<int>(fit.phi.size());
  out.parameters = fit.phi;
  out.standard_errors = fit.covariance.size() ? Eigen::VectorXd(fit.covariance.diagonal().cwiseMax(0.0).cwiseSqrt())
                                              : Eigen::VectorXd::Constant(p, kNan);
  for (int a = 0; a < p; ++a) {
    if (!determined[static_cast<std::size_t>(a)]) {
      out.parameters(a) = kNan;
      out.standard_errors(a) = kNan;
    }
  }
  const Derived d = derive(fit.phi, kin.moving);
  Eigen::VectorXd values = d.values();
  Eigen::VectorXd se = Eigen::VectorXd::Constant(22, kNan);
  if (fit.covariance.size()) se = (d.D * fit.covariance * d.D.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index i = 0; i < 22; ++i) {
    if (!depends_on_determined(d.D, i, determined)) {
      values(i) = kNan;
      se(i) = kNan;
    }
  }
  if (!kin.moving) {
    values.segment(4, 12).setConstant(kNan);
    se.segment(4, 12).setConstant(kNan);
  }
  out.mass = values(0);
  out.center_of_mass = values.segment<3>(1);
  out.inertia = values.segment<9>(4).reshaped(3, 3);
  out.principal.moments = values.segment<3>(13);
  out.principal.axes = kin.moving && values.segment<3>(13).allFinite() ? d.principal.axes
                                                                      : Eigen::Matrix3d(Eigen::Matrix3d::Constant(kNan));
  out.inertia_origin = kin.moving && out.inertia.allFinite() ? d.I_o : Eigen::Matrix3d(Eigen::Matrix3d::Constant(kNan));
  out.force_bias = values.segment<3>(16);
  out.torque_bias = values.segment<3>(19);
  out.mass_se = se(0);
  out.center_of_mass_se = se.segment<3>(1);
  out.inertia_se = se.segment<9>(4).reshaped(3, 3);
  out.principal_moments_se = se.segment<3>(13);
  out.force_bias_se = se.segment<3>(16);
  out.torque_bias_se = se.segment<3>(19);
  out.residuals = fit.residuals;
  for (int i = 0; i < 6; ++i) {
    out.residual_rms(i) = std::sqrt(fit.residuals.col(i).squaredNorm() / static_cast<double>(std::max<Eigen::Index>(kin.samples(), 1)));
  }

  if (robust) {
    out.robust = spdfit::detail::robust_report(request.robust, robust->tuning, robust->weights, robust->scale, robust->iterations,
                                               robust->converged);
    // The samples' numbers as the log's data rows (`rows` chooses among them).
    for (std::uint64_t& row : out.robust->rows_downweighted) {
      if (!rows.empty() && row >= 1 && row <= rows.size()) row = static_cast<std::uint64_t>(rows[row - 1] + 1);
    }
    if (!robust->converged) {
      out.warnings.emplace_back(Code::NotConverged,
                                "the robust fit's weights had not settled after " + std::to_string(robust->iterations) +
                                    " reweightings: the last fit is returned",
                                "robust");
    }
  }

  // What the user should know.
  if (!fit.converged) {
    out.warnings.push_back(Warning(Code::NotConverged, "the optimizer did not converge" + (fit.failure.empty() ? std::string() : ": " + fit.failure) +
                           "; the estimate is the last iterate"));
  }
  if (!fit.identifiability.undetermined.empty()) {
    std::string list;
    for (const physical::UndeterminedCombination& u : fit.identifiability.undetermined)
      list += (list.empty() ? "" : "; ") + u.text;
    out.warnings.push_back(Warning(Code::RankDeficient, 
        "the poses do not determine " + std::to_string(fit.identifiability.undetermined.size()) +
        (fit.identifiability.undetermined.size() == 1 ? " combination" : " combinations") + " of the parameters (" + list +
        "): the parameters they reach are reported as null. The samples have " +
        std::to_string(kin.distinct_orientations) + " distinct gravity " +
        (kin.distinct_orientations == 1 ? "direction" : "directions") +
        " in the sensor frame: log at least 3 (rotations about the vertical add none)"));
  }
  if (kin.moving && !kin.rotating) {
    out.warnings.push_back(Warning(Code::PhysicalNotice, "omega and alpha are zero in every row: nothing excites the inertia"));
  }
  if (out.constraint_active && !kin.moving) {
    out.warnings.push_back(Warning(Code::Boundary, "the unconstrained fit's mass is " + format_number(fit.phi_ls(0)) + " kg (standard error " +
                           format_number(fit.mass_ls_se) +
                           " kg): the constraint m >= 0 is active, the mass is 0 and the centre of mass undefined; the "
                           "payload is lighter than the data resolve"));
  } else if (out.constraint_active) {
    out.warnings.push_back(Warning(Code::Boundary, "the estimate lies on the boundary of physical consistency (the pseudo-inertia's smallest "
                           "eigenvalue is " + format_number(fit.pseudo_min) +
                           " kg): the constraint is active, as for a payload whose mass lies on a plane or a line"));
  }
  if (!request.consistent && !out.physically_consistent) {
    out.warnings.push_back(Warning(Code::PhysicalNotice, std::string("the unconstrained estimate is not physically consistent (") +
                           (kin.moving ? "the pseudo-inertia's smallest eigenvalue is " + format_number(fit.pseudo_min) + " kg"
                                       : "its mass is negative") +
                           "): no rigid body has these mass properties"));
  }

  if (request.bootstrap > 0) {
    const auto replicates = static_cast<std::size_t>(request.bootstrap);
    std::vector<std::optional<Eigen::VectorXd>> draws(replicates);
    IdentifyRequest quiet = request;
    quiet.bootstrap = 0;
    quiet.threads = 1;
    spdfit::detail::parallel_for(replicates, request.threads, [&](std::size_t r) {
      const std::vector<std::uint32_t> c = physical::detail::resample_counts(kin.samples(), request.seed, r);
      const std::vector<double> counts(c.begin(), c.end());
      try {
        // A robust estimate's replicates: each resample reweighted from the estimate and its scale.
        const Fit f = robust ? detail::robust_fit_payload(kin, quiet, noise, counts, false, &fit.phi, robust->scale).fit
                             : detail::fit_payload(kin, quiet, noise, counts, false);
        Eigen::VectorXd v = derive(f.phi, kin.moving).values();
        for (Eigen::Index i = 0; i < 22; ++i)
          if (!std::isfinite(values(i))) v(i) = kNan;
        draws[r] = v;
      } catch (const std::exception&) {
      }
    });
    const physical::detail::EntrySummary s = physical::detail::summarize(22, draws, request.confidence);
    PayloadEstimate::Bootstrap b;
    b.replicates = request.bootstrap;
    b.seed = request.seed;
    b.level = request.confidence;
    for (const auto& r : draws) b.failed += r ? 0 : 1;
    const auto group = [&](Eigen::Index begin, Eigen::Index rows, Eigen::Index cols) {
      Interval in;
      in.standard_errors = s.standard_errors.segment(begin, rows * cols).reshaped(rows, cols);
      in.lower = s.lower.segment(begin, rows * cols).reshaped(rows, cols);
      in.upper = s.upper.segment(begin, rows * cols).reshaped(rows, cols);
      return in;
    };
    b.mass = group(0, 1, 1);
    b.center_of_mass = group(1, 3, 1);
    b.inertia = group(4, 3, 3);
    b.principal_moments = group(13, 3, 1);
    b.force_bias = group(16, 3, 1);
    b.torque_bias = group(19, 3, 1);
    out.bootstrap = b;
    if (b.failed > 0) {
      out.warnings.push_back(Warning(Code::BootstrapNotice, std::to_string(b.failed) + " of " + std::to_string(b.replicates) +
                             " bootstrap replicates failed and are left out"));
    }
  }
  return out;
}

std::string urdf_text(const PayloadEstimate& estimate, const IdentifyRequest& request) {
  if (!estimate.moving) {
    throw OptionError("`urdf` needs the inertia, which static poses do not determine: log moving poses "
                      "(`omega_cols` with `accel_cols` or `specific_force_cols`)", Code::OptionNotApplicable);
  }
  RigidBodyInertia body;
  body.mass = estimate.mass;
  body.center_of_mass = estimate.center_of_mass;
  body.inertia = estimate.inertia;
  if (!(body.mass > 0.0) || !body.inertia.allFinite() || !body.center_of_mass.allFinite()) {
    throw InputError("cannot write the payload as a URDF link: its mass, centre of mass or inertia is not "
                                "determined (see the warnings)", Code::PhysicalData);
  }
  return urdf_link(body, request.link_name, request.precision);
}

}  // namespace spdfit::payload
