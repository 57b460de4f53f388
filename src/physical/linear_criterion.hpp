// Internal: the least-squares criterion of a model linear in its parameters, from the triangular
// factor of its (whitened) regressor, in the solver's coordinates theta (cone.hpp), optionally
// with the log-determinant divergence of each body's pseudo-inertia from a prior's (Lee, Wensing
// and Park 2020, "Geometric robot dynamic identification: a convex programming approach"):
//
//     f(theta) = (||X theta - y||^2 + rho^2) / f0 + w sum_k D(P_k || P0_k),
//     D(P || P0) = tr(P0^-1 P) - log det(P0^-1 P) - 4,
//
// X = R11 M (R11 the factor of the regressor, M the map from theta to its columns' parameters),
// y = R12, rho = ||R22||. Convex: its Hessian 2 X^T X / f0 (+ w sum P_k^-1 (x) P_k^-1) is formed
// once. With a prior the criterion is defined only inside the cone (the divergence is +inf on its
// boundary).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "physical/cone.hpp"
#include "physical/cone_solver.hpp"

namespace spdfit::physical::detail {

class LinearCriterion : public Criterion {
 public:
  /// X (q x p), y (q), rho2 = the residual no parameter can reach, f0 > 0 the normalization.
  LinearCriterion(Eigen::MatrixXd X, Eigen::VectorXd y, double rho2, double f0);

  /// Adds w sum_k D(P_k || prior[k]) for the first prior.size() bodies of `layout` (each prior
  /// positive definite, in the same coordinates: scaled by the body's length).
  void set_prior(const ConeLayout& layout, std::vector<Eigen::Matrix4d> prior, double weight);

  bool evaluate(const Eigen::VectorXd& theta, int order, Evaluation& out) const override;

  /// Adds ridge ||theta||^2 (a tiny multiple of X^T X's scale): where the data leave directions
  /// undetermined and nothing else bounds them, the barrier's -log det would push the iterates to
  /// infinity along them; the ridge keeps the barrier problems bounded and picks, among the
  /// minimizers, the one of least norm in theta (to the ridge's relative size in the rest).
  void set_ridge(double ridge);

  /// ||X theta - y||^2 + rho^2: the criterion in the data's (whitened) units, without the prior.
  double residual_squares(const Eigen::VectorXd& theta) const;

  double f0() const { return f0_; }
  const Eigen::MatrixXd& design() const { return X_; }

 private:
  Eigen::MatrixXd X_;
  Eigen::VectorXd y_;
  double rho2_ = 0.0, f0_ = 1.0;
  Eigen::MatrixXd gram_;  // 2 X^T X / f0
  std::vector<Eigen::Matrix4d> prior_inverse_;
  double prior_log_det_ = 0.0;  // sum_k log det prior[k]
  double weight_ = 0.0;
  double ridge_ = 0.0;
};

}  // namespace spdfit::physical::detail
