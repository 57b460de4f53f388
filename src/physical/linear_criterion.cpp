#include "physical/linear_criterion.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

namespace spdfit::physical::detail {

LinearCriterion::LinearCriterion(Eigen::MatrixXd X, Eigen::VectorXd y, double rho2, double f0)
    : X_(std::move(X)), y_(std::move(y)), rho2_(rho2), f0_(f0) {
  if (!(f0_ > 0.0) || !std::isfinite(f0_)) f0_ = 1.0;
  // The Hessian of the squares: X^T X as the product of X (q x p, q = p after a factor) with itself.
  gram_ = (2.0 / f0_) * (X_.transpose() * X_);
  gram_ = 0.5 * (gram_ + gram_.transpose()).eval();
}

void LinearCriterion::set_prior(const ConeLayout& layout, std::vector<Eigen::Matrix4d> prior, double weight) {
  if (static_cast<int>(prior.size()) > layout.bodies) throw std::invalid_argument("set_prior: more priors than bodies");
  prior_inverse_.clear();
  prior_log_det_ = 0.0;
  for (const Eigen::Matrix4d& P0 : prior) {
    const Eigen::LLT<Eigen::Matrix4d> llt(P0);
    if (llt.info() != Eigen::Success) throw std::invalid_argument("set_prior: a prior is not positive definite");
    prior_inverse_.push_back(llt.solve(Eigen::Matrix4d::Identity()));
    prior_log_det_ += 2.0 * llt.matrixLLT().diagonal().array().log().sum();
  }
  weight_ = weight;
}

void LinearCriterion::set_ridge(double ridge) {
  gram_.diagonal().array() += 2.0 * (ridge - ridge_);
  ridge_ = ridge;
}

double LinearCriterion::residual_squares(const Eigen::VectorXd& theta) const {
  return (X_ * theta - y_).squaredNorm() + rho2_;
}

bool LinearCriterion::evaluate(const Eigen::VectorXd& theta, int order, Evaluation& out) const {
  const Eigen::VectorXd r = X_ * theta - y_;
  out.f = (r.squaredNorm() + rho2_) / f0_ + ridge_ * theta.squaredNorm();
  if (order >= 1) out.g = (2.0 / f0_) * (X_.transpose() * r) + (2.0 * ridge_) * theta;
  if (order >= 2) out.H = gram_;
  if (weight_ > 0.0 && !prior_inverse_.empty()) {
    for (std::size_t k = 0; k < prior_inverse_.size(); ++k) {
      const int body = static_cast<int>(k);
      const Eigen::Matrix4d P = body_matrix(theta, body);
      const Eigen::LLT<Eigen::Matrix4d> llt(P);
      if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0.0)) return false;
      const double log_det = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
      // D(P || P0) = tr(P0^-1 P) - log det P + log det P0 - 4.
      out.f += weight_ * (prior_inverse_[k].cwiseProduct(P).sum() - log_det - 4.0);
      if (order < 1) continue;
      const Eigen::Matrix4d Pinv = llt.solve(Eigen::Matrix4d::Identity());
      const int base = kBodyCoordinates * body;
      for (int a = 0; a < kBodyCoordinates; ++a)
        out.g(base + a) += weight_ * (coordinate(prior_inverse_[k], a) - coordinate(Pinv, a));
      if (order < 2) continue;
      for (int a = 0; a < kBodyCoordinates; ++a) {
        const Eigen::Matrix4d B = Pinv * basis_matrix(a) * Pinv;
        for (int b = 0; b < kBodyCoordinates; ++b) out.H(base + b, base + a) += weight_ * coordinate(B, b);
      }
    }
    if (order >= 2) out.H = 0.5 * (out.H + out.H.transpose()).eval();
    out.f += weight_ * prior_log_det_;
  }
  return std::isfinite(out.f);
}

}  // namespace spdfit::physical::detail
