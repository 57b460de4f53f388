#include "payload/eiv.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <atomic>
#include <cmath>

#include "numerics/parallel.hpp"

namespace spdfit::payload::detail {

namespace {

// Samples per chunk of the parallel sum: the chunks' partial sums are added in order, so the
// result does not depend on the threads.
constexpr Eigen::Index kChunk = 2048;

using RowMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, 16>;
using SquareMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 16, 16>;
using ParamVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 16, 1>;

struct Partial {
  double f = 0.0;
  ParamVector g;
  SquareMatrix H, S;
  bool ok = true;
};

}  // namespace

EivCriterion::EivCriterion(const Kinematics& kin, const ParameterLayout& layout, Eigen::MatrixXd M,
                           const Eigen::MatrixXd& noise_w, const Eigen::MatrixXd& noise_x, unsigned threads,
                           std::vector<double> counts)
    : kin_(kin), layout_(layout), M_(std::move(M)), threads_(threads), counts_(std::move(counts)) {
  noise_w_ = noise_w.size() ? Eigen::Matrix<double, 6, 6>(noise_w) : Eigen::Matrix<double, 6, 6>::Zero();
  noise_x_ = noise_x.size() ? Eigen::Matrix<double, 9, 9>(noise_x) : Eigen::Matrix<double, 9, 9>::Zero();
}

bool EivCriterion::evaluate_phi(const Eigen::VectorXd& phi, int order, double& f, Eigen::VectorXd* g,
                                Eigen::MatrixXd* H, Eigen::MatrixXd* scores) const {
  const int p = layout_.size(), q = layout_.inertial();
  const Eigen::Index m = kin_.samples();
  const Eigen::Index chunks = (m + kChunk - 1) / kChunk;
  std::vector<Partial> partial(static_cast<std::size_t>(chunks));
  spdfit::detail::parallel_for(static_cast<std::size_t>(chunks), threads_, [&](std::size_t c) {
    Partial& out = partial[c];
    out.g.setZero(p);
    if (order >= 2) out.H.setZero(p, p);
    if (scores) out.S.setZero(p, p);
    RowMatrix X(6, p), V(6, p);
    Matrix69 J[10];
    Eigen::Matrix<double, 9, Eigen::Dynamic, Eigen::ColMajor, 9, 10> K(9, q);
    Eigen::Matrix<double, 6, 10> CU;
    const Eigen::Index begin = static_cast<Eigen::Index>(c) * kChunk, end = std::min(m, begin + kChunk);
    for (Eigen::Index k = begin; k < end; ++k) {
      const double weight = counts_.empty() ? 1.0 : counts_[static_cast<std::size_t>(k)];
      if (weight == 0.0) continue;
      sample_regressor(kin_, k, layout_, X);
      jacobian_basis(kin_, k, layout_, J);
      Matrix69 Jk = Matrix69::Zero();
      for (int a = 0; a < q; ++a) Jk += phi(a) * J[a];
      const Eigen::Matrix<double, 6, 1> r = X * phi - kin_.wrench.col(k);
      Eigen::Matrix<double, 6, 6> C = Jk * noise_x_ * Jk.transpose() + noise_w_;
      C = 0.5 * (C + C.transpose()).eval();
      const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(C);
      if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0.0)) {
        out.ok = false;
        return;
      }
      const Eigen::Matrix<double, 6, 1> u = llt.solve(r);
      out.f += weight * r.dot(u);
      if (order < 1 && !scores) continue;
      const Eigen::Matrix<double, 9, 1> v = noise_x_ * (Jk.transpose() * u);
      ParamVector gk(p);
      gk = X.transpose() * u;  // half the gradient of r^T C^-1 r along the columns of X
      for (int a = 0; a < q; ++a) {
        K.col(a) = J[a].transpose() * u;
        gk(a) -= K.col(a).dot(v);
      }
      out.g += (2.0 * weight) * gk;
      if (scores) out.S.noalias() += weight * gk * gk.transpose();
      if (order < 2) continue;
      for (int a = 0; a < q; ++a) CU.col(a) = J[a] * v + Jk * (noise_x_ * K.col(a));
      V = X;
      V.leftCols(q) -= CU.leftCols(q);
      const RowMatrix LV = llt.matrixL().solve(V);
      out.H.noalias() += (2.0 * weight) * (LV.transpose() * LV);
      out.H.topLeftCorner(q, q).noalias() -= (2.0 * weight) * (K.transpose() * noise_x_ * K);
    }
  });
  f = 0.0;
  if (g) g->setZero(p);
  if (H) H->setZero(p, p);
  if (scores) scores->setZero(p, p);
  for (const Partial& part : partial) {
    if (!part.ok) return false;
    f += part.f;
    if (g && order >= 1) *g += part.g;
    if (H && order >= 2) *H += part.H;
    if (scores) *scores += part.S;
  }
  if (H && order >= 2) *H = (0.5 * (*H + H->transpose())).eval();
  return std::isfinite(f);
}

bool EivCriterion::evaluate(const Eigen::VectorXd& theta, int order, physical::detail::Evaluation& out) const {
  const Eigen::VectorXd phi = M_ * theta;
  double f = 0.0;
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  if (!evaluate_phi(phi, order, f, order >= 1 ? &g : nullptr, order >= 2 ? &H : nullptr)) return false;
  out.f = f / f0_;
  if (order >= 1) out.g = M_.transpose() * g / f0_;
  if (order >= 2) out.H = M_.transpose() * H * M_ / f0_;
  return std::isfinite(out.f);
}

}  // namespace spdfit::payload::detail
