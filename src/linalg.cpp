#include "linalg.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spdfit::detail {

Svd svd(const Eigen::Ref<const MatrixXd>& A, bool compute_u, bool compute_v) {
  Svd out;
  svd_into(A, out, compute_u, compute_v);
  return out;
}

VectorXd singular_values(const Eigen::Ref<const MatrixXd>& A) { return svd(A, false, false).s; }

Index numerical_rank(const Eigen::Ref<const VectorXd>& s, double cutoff) {
  if (s.size() == 0 || !(s(0) > 0.0)) return 0;
  const double threshold = cutoff * s(0);
  Index rank = 0;
  while (rank < s.size() && s(rank) > threshold) ++rank;
  return rank;
}

double condition_number(const Eigen::Ref<const VectorXd>& s) {
  if (s.size() == 0) return std::numeric_limits<double>::infinity();
  const double smin = s(s.size() - 1);
  if (!(smin > 0.0)) return std::numeric_limits<double>::infinity();
  return s(0) / smin;
}

MatrixXd triangular_factor(const Eigen::Ref<const MatrixXd>& A) {
  MatrixXd R;
  triangular_factor_into<MatrixXd>(A, R);
  return R;
}

std::optional<int> scale_exponent(const Eigen::Ref<const MatrixXd>& X) {
  if (X.size() == 0) return std::nullopt;
  const double biggest = X.cwiseAbs().maxCoeff();
  if (!(biggest > 0.0)) return std::nullopt;
  int e = 0;
  std::frexp(biggest, &e);  // biggest = f 2^e with f in [0.5, 1): |x| < 2^e
  return e;
}

}  // namespace spdfit::detail
