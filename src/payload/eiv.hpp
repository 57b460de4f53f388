// Internal: the errors-in-variables criterion of the payload's wrench model,
//
//     F(phi) = sum_k r_k^T C_k^-1 r_k,  r_k = X_k phi - w_k,  C_k = J_k Sigma_x J_k^T + Sigma_w,
//
// J_k = sum_a phi_a J_a,k the model wrench's Jacobian in the pose signals x = (s, omega, alpha)
// (linear in phi), with its exact gradient and Hessian. For a model linear in the noisy signals
// (s, alpha) the noise part of r_k is J_k e - eps, whose covariance is C_k at the same phi: the
// criterion's expectation is minimized at the truth (the maximum-likelihood criterion after
// profiling out the true signals, to first order in omega's noise, whose second-order mean is a
// constant the biases absorb). As a Criterion of the solver's coordinates theta = M^-1 phi.
#pragma once

#include <array>
#include <mutex>
#include <vector>

#include <Eigen/Core>

#include "payload/kinematics.hpp"
#include "payload/wrench_model.hpp"
#include "physical/cone_solver.hpp"

namespace spdfit::payload::detail {

class EivCriterion : public physical::detail::Criterion {
 public:
  /// `M` maps theta to phi (p x p); Sigma_w 6 x 6 and Sigma_x 9 x 9 (positive semidefinite and block
  /// diagonal in (s, omega, alpha), as noise_covariances makes it, else std::invalid_argument; C_k
  /// positive definite at the phi evaluated); `counts` (empty: 1 each) weighs the samples (the
  /// bootstrap's resamples).
  EivCriterion(const Kinematics& kin, const ParameterLayout& layout, Eigen::MatrixXd M, const Eigen::MatrixXd& noise_w,
               const Eigen::MatrixXd& noise_x, unsigned threads, std::vector<double> counts = {});

  /// f0: the criterion is reported as F / f0 (about 1 at the start).
  void set_normalization(double f0) { f0_ = f0 > 0.0 ? f0 : 1.0; }
  double f0() const { return f0_; }

  bool evaluate(const Eigen::VectorXd& theta, int order, physical::detail::Evaluation& out) const override;
  int trial_order() const override { return 2; }

  /// Each sample's residual norm as the criterion weighs it, sqrt(r_k^T C_k^-1 r_k) at phi (the
  /// robust fit's); NaN where C_k is not positive definite.
  Eigen::VectorXd sample_norms(const Eigen::VectorXd& phi) const;

  /// With `keep`, every evaluation of order 2 also sums the scores, so that the sandwich's request
  /// for them at the minimizer (where Newton's method evaluated last) needs no pass of its own.
  void set_keep_scores(bool keep) { keep_scores_ = keep; }
  /// `counts` as reliability weights (a robust fit's): the scores weighed by their squares.
  void set_reliability_weights(bool reliability) { reliability_ = reliability; }

  /// F, its gradient and Hessian in phi (unnormalized), and with `scores` the sum over samples of
  /// the outer products of each sample's half-gradient (the sandwich's middle). False when some C_k
  /// is not positive definite.
  bool evaluate_phi(const Eigen::VectorXd& phi, int order, double& f, Eigen::VectorXd* g, Eigen::MatrixXd* H,
                    Eigen::MatrixXd* scores = nullptr) const;

 private:
  const Kinematics& kin_;
  ParameterLayout layout_;
  Eigen::MatrixXd M_;
  Eigen::Matrix<double, 6, 6> noise_w_;
  std::array<Eigen::Matrix3d, 3> noise_x_;  ///< Sigma_x's diagonal blocks (s, omega, alpha)
  unsigned threads_;
  std::vector<double> counts_;
  double f0_ = 1.0;
  bool keep_scores_ = false;
  bool reliability_ = false;
  // The last evaluation: a request at the same phi (to the bit) of no higher order is answered
  // from it (Newton's method evaluates the accepted trial point again, the KKT certificate and the
  // sandwich evaluate the minimizer again).
  struct Last {
    Eigen::VectorXd phi;
    int order = -1;
    bool has_scores = false, ok = false;
    double f = 0.0;
    Eigen::VectorXd g;
    Eigen::MatrixXd H, S;
  };
  mutable std::mutex last_mutex_;
  mutable Last last_;
};

}  // namespace spdfit::payload::detail
