#include "small_least_squares.hpp"

#include "numerics/least_squares.hpp"
#include "spdfit/rank.hpp"

namespace spdfit::linkage::detail {

using Eigen::MatrixXd;
using Eigen::VectorXd;

SmallLeastSquares small_least_squares(const Eigen::Ref<const MatrixXd>& M, const Eigen::Ref<const VectorXd>& rhs,
                                      double threshold) {
  // One least-squares home for every path (numerics/least_squares.hpp): the rank decided on M's
  // columns scaled to unit norm, the full-rank solution refined with accurate residuals.
  const spdfit::detail::LeastSquaresSolution ls =
      spdfit::detail::equilibrated_least_squares(M, rhs, rank_cutoff(threshold, M.rows(), M.cols()));
  SmallLeastSquares out;
  out.x = ls.X.col(0);
  out.rank = ls.rank;
  out.condition_number = spdfit::detail::condition_number(ls.unscaled.s);
  out.scaled_condition_number = spdfit::detail::condition_number(ls.scaled.s);
  out.used_svd = ls.rank < M.cols();
  return out;
}

}  // namespace spdfit::linkage::detail
