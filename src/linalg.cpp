#include "linalg.hpp"

#include <Eigen/Householder>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "one_sided_jacobi.hpp"

namespace spdfit::detail {

namespace {
// Up to this size the one-sided Jacobi SVD (accurate for the small singular values the
// estimators depend on, see one_sided_jacobi.hpp) is used; above it divide and conquer, which
// is much faster for large n.
constexpr Index kJacobiMaxSize = 64;
}  // namespace

Svd svd(const Eigen::Ref<const MatrixXd>& A, bool compute_u, bool compute_v) {
  Svd out;
  if (A.cols() <= kJacobiMaxSize && A.rows() >= A.cols()) {
    MatrixXd G = A;
    MatrixXd V;
    one_sided_jacobi(G, compute_v ? &V : static_cast<MatrixXd*>(nullptr));
    const Index n = A.cols();
    const VectorXd norms = G.colwise().norm();
    // Sort descending: the order every caller (ranks, TLS's trailing vectors) relies on.
    std::vector<Index> order(n);
    std::iota(order.begin(), order.end(), Index{0});
    std::stable_sort(order.begin(), order.end(), [&](Index i, Index j) { return norms(i) > norms(j); });
    out.s.resize(n);
    if (compute_u) out.U.resize(A.rows(), n);
    if (compute_v) out.V.resize(n, n);
    for (Index k = 0; k < n; ++k) {
      const Index j = order[k];
      out.s(k) = norms(j);
      if (compute_u) {
        // A zero singular value has no defined left vector; zero is what the callers expect.
        if (norms(j) > 0.0)
          out.U.col(k) = G.col(j) / norms(j);
        else
          out.U.col(k).setZero();
      }
      if (compute_v) out.V.col(k) = V.col(j);
    }
    return out;
  }
  unsigned options = 0;
  if (compute_u) options |= Eigen::ComputeThinU;
  if (compute_v) options |= Eigen::ComputeThinV;
  Eigen::BDCSVD<MatrixXd> dec(A, options);
  out.s = dec.singularValues();
  if (compute_u) out.U = dec.matrixU();
  if (compute_v) out.V = dec.matrixV();
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
  const Index cols = A.cols();
  MatrixXd R = MatrixXd::Zero(cols, cols);
  if (A.rows() == 0) return R;
  Eigen::HouseholderQR<MatrixXd> qr(A);
  const Index k = std::min(A.rows(), cols);
  R.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  return R;
}

void make_symmetric_from_lower(MatrixXd& X) { X.triangularView<Eigen::StrictlyUpper>() = X.transpose(); }

MatrixXd symmetric_part(const Eigen::Ref<const MatrixXd>& X) {
  // Halving first keeps entries near the double range finite; addition commutes, so the
  // result is exactly symmetric.
  return 0.5 * X + 0.5 * X.transpose();
}

std::optional<int> scale_exponent(const Eigen::Ref<const MatrixXd>& X) {
  if (X.size() == 0) return std::nullopt;
  const double biggest = X.cwiseAbs().maxCoeff();
  if (!(biggest > 0.0)) return std::nullopt;
  int e = 0;
  std::frexp(biggest, &e);  // biggest = f 2^e with f in [0.5, 1): |x| < 2^e
  return e;
}

MatrixXd times_power_of_two(const Eigen::Ref<const MatrixXd>& X, int e) {
  // 2^e is itself a normal double for |e| <= 1022; beyond that (denormal data, say) scale each
  // entry with ldexp so the factor never overflows or underflows on its own.
  if (e >= -1022 && e <= 1022) return X * std::ldexp(1.0, e);
  return X.unaryExpr([e](double x) { return std::ldexp(x, e); });
}

}  // namespace spdfit::detail
