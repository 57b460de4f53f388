#include "small_least_squares.hpp"

#include "spdfit/rank.hpp"

#include <algorithm>
#include <limits>

#include <Eigen/QR>
#include <Eigen/SVD>

namespace spdfit::linkage::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

SmallLeastSquares small_least_squares(const Eigen::Ref<const MatrixXd>& M, const Eigen::Ref<const VectorXd>& rhs,
                                      double threshold) {
  const Index m = M.rows(), n = M.cols();
  const double cutoff = rank_cutoff(threshold, m, n);
  SmallLeastSquares out;
  Eigen::HouseholderQR<MatrixXd> qr(M);
  const Index k = std::min(m, n);
  MatrixXd R = MatrixXd::Zero(n, n);
  R.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  const VectorXd s = Eigen::JacobiSVD<MatrixXd>(R).singularValues();
  const double inf = std::numeric_limits<double>::infinity();
  out.condition_number = s(n - 1) > 0.0 ? s(0) / s(n - 1) : inf;
  out.rank = numerical_rank(s, cutoff);
  if (out.rank == n) {
    out.x = R.triangularView<Eigen::Upper>().solve((qr.householderQ().transpose() * rhs).head(n));
    return out;
  }
  // Rank-deficient: the minimum-norm solution with the small singular values edited (eq. 3.21).
  out.used_svd = true;
  Eigen::JacobiSVD<MatrixXd> svd(M, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Index r = out.rank;
  out.x = svd.matrixV().leftCols(r) *
          (svd.singularValues().head(r).cwiseInverse().asDiagonal() * (svd.matrixU().leftCols(r).transpose() * rhs));
  return out;
}

}  // namespace spdfit::linkage::detail
