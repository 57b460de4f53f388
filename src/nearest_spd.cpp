#include "spdfit/nearest_spd.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

NearestSpdResult nearest_spd(const Eigen::Ref<const MatrixXd>& X, double min_eig) {
  if (X.rows() != X.cols() || X.size() == 0) {
    throw std::invalid_argument("nearest_spd needs a non-empty square matrix, got " +
                                std::to_string(X.rows()) + "x" + std::to_string(X.cols()));
  }
  if (!X.allFinite()) throw std::invalid_argument("nearest_spd: the matrix contains NaN or Inf");
  if (!std::isfinite(min_eig) || min_eig < 0.0) {
    throw std::invalid_argument("nearest_spd: min_eig must be a finite number >= 0");
  }
  // Higham 1988: the nearest symmetric matrix is S = (X + X^T)/2, and the nearest one with
  // eigenvalues >= min_eig clips the eigenvalues of S = W diag(lambda) W^T. For min_eig = 0 this
  // is (S + H)/2 with H the symmetric polar factor of S (thesis eq. 4.39).
  const MatrixXd S = detail::symmetric_part(X);
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(S);
  if (eig.info() != Eigen::Success) {
    throw std::runtime_error("nearest_spd: the symmetric eigensolver did not converge");
  }
  Eigen::VectorXd lambda = eig.eigenvalues();
  NearestSpdResult out;
  out.min_eigenvalue_before = lambda(0);
  for (Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) < min_eig) {
      lambda(i) = min_eig;
      ++out.clipped;
    }
  }
  if (out.clipped == 0) {
    out.X = S;  // already admissible: no rounding from re-assembly
  } else {
    const MatrixXd& W = eig.eigenvectors();
    out.X = MatrixXd::Zero(S.rows(), S.cols());
    // Lower triangle of W diag(lambda) W^T, mirrored: exactly symmetric.
    out.X.triangularView<Eigen::Lower>() = W * lambda.asDiagonal() * W.transpose();
    detail::make_symmetric_from_lower(out.X);
  }
  out.distance = (X - out.X).stableNorm();  // entries near the double range must not overflow
  return out;
}

}  // namespace spdfit
