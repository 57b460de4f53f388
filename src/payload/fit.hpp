// Internal: one payload fit from the samples' kinematics (identify.cpp), shared by the estimate
// and the bootstrap's replicates.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "payload/kinematics.hpp"
#include "payload/wrench_model.hpp"
#include "spdfit/physical/identifiability.hpp"

namespace spdfit::payload::detail {

struct Fit {
  ParameterLayout layout;
  Eigen::VectorXd phi;     ///< the estimate, every parameter (undetermined ones too)
  Eigen::VectorXd phi_ls;  ///< the unconstrained least-squares fit
  double mass_ls_se = 0.0; ///< its mass's standard error (the sandwich), when reported
  physical::Identifiability identifiability;
  double criterion = 0.0;
  physical::Certificate certificate;
  int iterations = 0;
  bool converged = true;
  std::string failure;
  bool active = false;           ///< the constraint is active at the estimate
  double pseudo_min = 0.0;       ///< lambda_min of the scaled pseudo-inertia (moving) or m (static)
  double length = 1.0;           ///< L of the scaled pseudo-inertia (m)
  Eigen::MatrixXd covariance;    ///< of phi (sandwich), when reported
  Eigen::MatrixXd residuals;     ///< samples x 6, when reported
};

/// The fit of the request's criterion to `kin` with the noise model `noise`; `counts` (empty: 1
/// each) weighs the samples: as frequencies (a bootstrap resample's whole counts), or with
/// `frequency` false as reliability weights >= 0 (a robust fit's: the sandwich's middle then
/// weighs each sample's score by the square). `reported` adds the certificate, the covariance and
/// the residuals. Throws SignalError for a wrench noise covariance that is singular.
Fit fit_payload(const Kinematics& kin, const IdentifyRequest& request, const NoiseCovariances& noise,
                const std::vector<double>& counts, bool reported, bool frequency = true);

/// The robust fit of `request.robust` (an M-estimator by reweighting): each sample weighted by
/// the loss's weight of its residual norm (sample_residual_norms) over the scale (Huber:
/// re-estimated each time as the norms' median over the chi(6) median), then fit_payload of the
/// weighted samples, until the parameters move by less than 1e-8 of themselves (at most 50
/// times). From the criterion's plain fit; Tukey from Huber's fit and scale (not a
/// high-breakdown start). `start` (with `start_scale`): a bootstrap replicate's reweighting from
/// the estimate. `counts` multiply the weights. The last weighted fit is `reported` as asked.
struct RobustPayloadFit {
  Fit fit;
  Eigen::VectorXd weights;  ///< each sample's final robust weight (counts not included)
  double tuning = 0.0;      ///< the loss's constant k used
  double scale = 0.0;
  int iterations = 0;
  bool converged = false;
};
RobustPayloadFit robust_fit_payload(const Kinematics& kin, const IdentifyRequest& request, const NoiseCovariances& noise,
                                    const std::vector<double>& counts, bool reported,
                                    const Eigen::VectorXd* start = nullptr, double start_scale = 0.0);

}  // namespace spdfit::payload::detail
