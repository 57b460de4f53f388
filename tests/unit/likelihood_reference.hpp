// The likelihood criterion with a noise model, computed row by row from the data: the reference
// the noise-model estimators' tests check spdfit's own criterion, gradients and minimizers against.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace spdfit::test {

/// sum_i r_i^T W^-1 r_i, W = X^T Sigma_A X + Sigma_B, r_i = X^T a_i - b_i (a_i, b_i the rows of A
/// and B as columns), for X square.
inline double likelihood_criterion(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& X,
                                   const Eigen::MatrixXd& Sa, const Eigen::MatrixXd& Sb) {
  const Eigen::LLT<Eigen::MatrixXd> llt(Eigen::MatrixXd(X.transpose() * Sa * X + Sb));
  double f = 0.0;
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const Eigen::VectorXd r = (A.row(i) * X - B.row(i)).transpose();
    f += r.dot(llt.solve(r));
  }
  return f;
}

}  // namespace spdfit::test
