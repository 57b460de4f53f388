#include "payload/eiv.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "numerics/parallel.hpp"

namespace spdfit::payload::detail {

namespace {

// Samples per chunk of the parallel sum: the chunks' partial sums are added in order, so the
// result does not depend on the threads.
constexpr Eigen::Index kChunk = 2048;

using ParamVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 16, 1>;
using SquareMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 16, 16>;

struct Partial {
  double f = 0.0;
  ParamVector g;
  SquareMatrix H, S;
  bool ok = true;
};

// Sample k's regressor X, residual r = X phi - w_k, J Sigma_x (JS, Sigma_x block diagonal) and the
// Cholesky factor of the residual's covariance C = Sigma_w + J Sigma_x J^T: what the criterion's
// terms and the robust fit's norms share. False when C is not positive definite.
template <int P>
bool sample_terms(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout, const Eigen::VectorXd& phi_in,
                  const Eigen::Matrix<double, P, 1>& phi, const Eigen::Matrix<double, 6, 6>& noise_w,
                  const std::array<Eigen::Matrix3d, 3>& noise_x, Eigen::Matrix<double, 6, P>& X, Matrix69& JS,
                  Eigen::Matrix<double, 6, 1>& r, Eigen::LLT<Eigen::Matrix<double, 6, 6>>& llt) {
  sample_regressor(kin, k, layout, X);
  const Matrix69 J = model_jacobian(kin, k, layout, phi_in);
  for (int b = 0; b < 3; ++b) JS.middleCols<3>(3 * b) = J.middleCols<3>(3 * b).lazyProduct(noise_x[b]);
  r = X * phi - kin.wrench.col(k);
  Eigen::Matrix<double, 6, 6> C = noise_w;
  C += JS.lazyProduct(J.transpose());
  llt.compute(C);
  return llt.info() == Eigen::Success && llt.matrixLLT().diagonal().minCoeff() > 0.0;
}

// sqrt(r_k^T C_k^-1 r_k) of samples [begin, end) into u (NaN where C_k is not positive definite).
template <int P>
void sample_norms_of(const Kinematics& kin, const ParameterLayout& layout, const Eigen::VectorXd& phi_in,
                     const Eigen::Matrix<double, 6, 6>& noise_w, const std::array<Eigen::Matrix3d, 3>& noise_x,
                     Eigen::Index begin, Eigen::Index end, Eigen::VectorXd& u) {
  const Eigen::Matrix<double, P, 1> phi = phi_in;
  Eigen::Matrix<double, 6, P> X;
  Matrix69 JS;
  Eigen::Matrix<double, 6, 1> r;
  Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt;
  for (Eigen::Index k = begin; k < end; ++k) {
    u(k) = sample_terms<P>(kin, k, layout, phi_in, phi, noise_w, noise_x, X, JS, r, llt)
               ? std::sqrt(std::max(r.dot(llt.solve(r)), 0.0))
               : std::numeric_limits<double>::quiet_NaN();
  }
}

// The sums of samples [begin, end) with the layout's sizes fixed at compile time (P parameters, Q
// of them inertial): each sample's work is a few small dense products, which fixed sizes unroll.
template <int P, int Q>
void accumulate(const Kinematics& kin, const ParameterLayout& layout, const Eigen::VectorXd& phi_in,
                const Eigen::Matrix<double, 6, 6>& noise_w, const std::array<Eigen::Matrix3d, 3>& noise_x,
                const std::vector<double>& counts, bool reliability, int order, bool scores, Eigen::Index begin,
                Eigen::Index end, Partial& out) {
  using Regressor = Eigen::Matrix<double, 6, P>;
  using Vector = Eigen::Matrix<double, P, 1>;
  using Square = Eigen::Matrix<double, P, P>;
  const Vector phi = phi_in;
  Vector g = Vector::Zero();
  Square H = Square::Zero(), S = Square::Zero();
  double f = 0.0;
  Regressor X, V, LV;
  Matrix69 JS;  // J Sigma_x
  Eigen::Matrix<double, 6, 1> r;
  Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt;
  Eigen::Matrix<double, 9, 10> Jt_u;
  Eigen::Matrix<double, 6, 10> J_v;
  for (Eigen::Index k = begin; k < end; ++k) {
    const double weight = counts.empty() ? 1.0 : counts[static_cast<std::size_t>(k)];
    if (weight == 0.0) continue;
    if (!sample_terms<P>(kin, k, layout, phi_in, phi, noise_w, noise_x, X, JS, r, llt)) {
      out.ok = false;
      return;
    }
    const Eigen::Matrix<double, 6, 1> u = llt.solve(r);
    f += weight * r.dot(u);
    if (order < 1 && !scores) continue;
    const Eigen::Matrix<double, 9, 1> v = JS.transpose() * u;  // Sigma_x J^T u
    jacobian_products(kin, k, layout, u, v, Jt_u, J_v);
    Vector gk = X.transpose() * u;  // half the gradient of r^T C^-1 r along the columns of X
    gk.template head<Q>().noalias() -= Jt_u.template leftCols<Q>().transpose() * v;
    g += (2.0 * weight) * gk;
    if (scores) S.noalias() += (reliability ? weight * weight : weight) * gk * gk.transpose();
    if (order < 2) continue;
    V = X;
    V.template leftCols<Q>() -= J_v.template leftCols<Q>();
    V.template leftCols<Q>() -= JS.lazyProduct(Jt_u.template leftCols<Q>());
    // L^-1 V by forward substitution, row by row (each row a vector of length P).
    const auto& L = llt.matrixLLT();
    for (int i = 0; i < 6; ++i) {
      auto row = LV.row(i);
      row = V.row(i);
      for (int j = 0; j < i; ++j) row -= L(i, j) * LV.row(j);
      row /= L(i, i);
    }
    H += (2.0 * weight) * LV.transpose().lazyProduct(LV);
    Eigen::Matrix<double, 9, Q> SK;  // Sigma_x dJ^T u
    for (int b = 0; b < 3; ++b) {
      SK.template middleRows<3>(3 * b) = noise_x[b].lazyProduct(Jt_u.template block<3, Q>(3 * b, 0));
    }
    H.template topLeftCorner<Q, Q>() -=
        (2.0 * weight) * Jt_u.template leftCols<Q>().transpose().lazyProduct(SK);
  }
  out.f = f;
  out.g = g;
  if (order >= 2) out.H = H;
  if (scores) out.S = S;
}

}  // namespace

EivCriterion::EivCriterion(const Kinematics& kin, const ParameterLayout& layout, Eigen::MatrixXd M,
                           const Eigen::MatrixXd& noise_w, const Eigen::MatrixXd& noise_x, unsigned threads,
                           std::vector<double> counts)
    : kin_(kin), layout_(layout), M_(std::move(M)), threads_(threads), counts_(std::move(counts)) {
  noise_w_ = noise_w.size() ? Eigen::Matrix<double, 6, 6>(noise_w) : Eigen::Matrix<double, 6, 6>::Zero();
  const Eigen::Matrix<double, 9, 9> full =
      noise_x.size() ? Eigen::Matrix<double, 9, 9>(noise_x) : Eigen::Matrix<double, 9, 9>::Zero();
  Eigen::Matrix<double, 9, 9> off = full;
  for (int b = 0; b < 3; ++b) {
    noise_x_[static_cast<std::size_t>(b)] = full.block<3, 3>(3 * b, 3 * b);
    off.block<3, 3>(3 * b, 3 * b).setZero();
  }
  if (off.cwiseAbs().maxCoeff() != 0.0) {
    throw std::invalid_argument("EivCriterion: Sigma_x must be block diagonal in (s, omega, alpha)");
  }
}

bool EivCriterion::evaluate_phi(const Eigen::VectorXd& phi, int order, double& f, Eigen::VectorXd* g,
                                Eigen::MatrixXd* H, Eigen::MatrixXd* scores) const {
  const int p = layout_.size();
  const std::lock_guard<std::mutex> lock(last_mutex_);
  const bool same_phi = last_.phi.size() == phi.size() &&
                        std::memcmp(last_.phi.data(), phi.data(), sizeof(double) * static_cast<std::size_t>(phi.size())) == 0;
  if (!same_phi || last_.order < order || (scores && !last_.has_scores)) {
    const bool with_scores = scores != nullptr || (keep_scores_ && order >= 2);
    const Eigen::Index m = kin_.samples();
    const Eigen::Index chunks = (m + kChunk - 1) / kChunk;
    std::vector<Partial> partial(static_cast<std::size_t>(chunks));
    spdfit::detail::parallel_for(static_cast<std::size_t>(chunks), threads_, [&](std::size_t c) {
      const Eigen::Index begin = static_cast<Eigen::Index>(c) * kChunk, end = std::min(m, begin + kChunk);
      if (layout_.moving) {
        accumulate<16, 10>(kin_, layout_, phi, noise_w_, noise_x_, counts_, reliability_, order, with_scores, begin, end,
                           partial[c]);
      } else {
        accumulate<10, 4>(kin_, layout_, phi, noise_w_, noise_x_, counts_, reliability_, order, with_scores, begin, end,
                          partial[c]);
      }
    });
    last_ = Last();
    last_.phi = phi;
    last_.order = order;
    last_.has_scores = with_scores;
    last_.g.setZero(p);
    last_.H.setZero(p, p);
    if (with_scores) last_.S.setZero(p, p);
    last_.ok = true;
    for (const Partial& part : partial) {
      if (!part.ok) {
        last_.ok = false;
        break;
      }
      last_.f += part.f;
      if (order >= 1) last_.g += part.g;
      if (order >= 2) last_.H += part.H;
      if (with_scores) last_.S += part.S;
    }
    if (last_.ok && order >= 2) last_.H = (0.5 * (last_.H + last_.H.transpose())).eval();
  }
  if (!last_.ok) return false;
  f = last_.f;
  if (g) {
    if (order >= 1) {
      *g = last_.g;
    } else {
      g->setZero(p);
    }
  }
  if (H) {
    if (order >= 2) {
      *H = last_.H;
    } else {
      H->setZero(p, p);
    }
  }
  if (scores) *scores = last_.S;
  return std::isfinite(f);
}

Eigen::VectorXd EivCriterion::sample_norms(const Eigen::VectorXd& phi) const {
  const Eigen::Index m = kin_.samples();
  Eigen::VectorXd u(m);
  const Eigen::Index chunks = (m + kChunk - 1) / kChunk;
  spdfit::detail::parallel_for(static_cast<std::size_t>(chunks), threads_, [&](std::size_t c) {
    const Eigen::Index begin = static_cast<Eigen::Index>(c) * kChunk, end = std::min(m, begin + kChunk);
    if (layout_.moving) {
      sample_norms_of<16>(kin_, layout_, phi, noise_w_, noise_x_, begin, end, u);
    } else {
      sample_norms_of<10>(kin_, layout_, phi, noise_w_, noise_x_, begin, end, u);
    }
  });
  return u;
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
