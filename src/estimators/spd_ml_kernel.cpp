#include "estimators/spd_ml_kernel.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "estimators/generalized_tls.hpp"
#include "estimators/spd_ml_boundary.hpp"
#include "estimators/spd_ml_model.hpp"
#include "estimators/newton_common.hpp"
#include "numerics/linalg.hpp"
#include "repair/nearest_spd_kernel.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using namespace trust_region;

namespace spd_ml {

bool criterion_at(const Problem& pr, Point& p) {
  const DynamicReduction& data = pr.data;
  p.G.noalias() = data.R11 * p.X;
  p.G -= data.R12;
  p.E.noalias() = p.G.transpose() * p.G;
  p.E += pr.E22;
  MatrixXd W = pr.noise.cov_b;
  const MatrixXd SX = pr.noise.cov_a * p.X;
  W.noalias() += p.X * SX;
  W = symmetric_part(W);
  const Eigen::LLT<MatrixXd> llt(W);
  if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().array() > 0.0).all()) return false;
  p.K = llt.solve(MatrixXd::Identity(W.rows(), W.cols()));
  p.K = symmetric_part(p.K);
  p.f = p.E.cwiseProduct(p.K).sum();  // tr(E K), both symmetric
  return std::isfinite(p.f) && p.f >= 0.0;
}

void gradient_at(const Problem& pr, const Point& p, Gradient& d) {
  d.M.noalias() = pr.data.R11.transpose() * p.G;
  d.N.noalias() = pr.noise.cov_a * p.X;
  d.F.noalias() = p.K * p.E * p.K;
  d.F = symmetric_part(d.F);
  d.MK.noalias() = d.M * p.K;
  d.NF.noalias() = d.N * d.F;
  d.gradX = d.MK + d.MK.transpose() - d.NF - d.NF.transpose();
}

void curvature_at(const Problem& pr, const Point& p, const Gradient& d, Curvature& c) {
  c.NK.noalias() = d.N * p.K;
  c.C1 = pr.P;
  {
    const MatrixXd MKN = d.MK * d.N.transpose();
    c.C1 -= MKN + MKN.transpose();
    c.C1.noalias() += d.NF * d.N.transpose();
  }
  c.C2.noalias() = c.NK * d.N.transpose();
  c.C2 -= pr.noise.cov_a;
  c.J = d.NF - d.MK;
}

MatrixXd gradient_magnitude(const Problem& pr, const Point& p) {
  const DynamicReduction& data = pr.data;
  const MatrixXd Xabs = p.X.cwiseAbs();
  const MatrixXd Gabs = data.R11.cwiseAbs() * Xabs + data.R12.cwiseAbs();
  const MatrixXd Mabs = data.R11.cwiseAbs().transpose() * Gabs;
  const MatrixXd Kabs = p.K.cwiseAbs();
  const MatrixXd Eabs = Gabs.transpose() * Gabs + pr.E22.cwiseAbs();
  const MatrixXd Fabs = Kabs * Eabs * Kabs;
  const MatrixXd Nabs = pr.noise.cov_a.cwiseAbs() * Xabs;
  const MatrixXd MKabs = Mabs * Kabs, NFabs = Nabs * Fabs;
  return MKabs + MKabs.transpose() + NFabs + NFabs.transpose();
}

// H_pq = sum_t tr(E_p U_t E_q V_t) + tr(E_q U_t E_p V_t) over the basis E_p of the packed
// coordinates (e_i e_i^T, (e_i e_j^T + e_j e_i^T) / sqrt 2), and tr(e_a e_b^T U e_c e_d^T V) = U_bc V_da.
void model_hessian(const MatrixXd* const* Us, const MatrixXd* const* Vs, int terms, MatrixXd& H) {
  const Index k = Us[0]->rows(), np = k * (k + 1) / 2;
  const double w = 1.0 / std::sqrt(2.0);
  H.resize(np, np);
  // The index pairs (alpha, beta) of each packed coordinate and their weights.
  struct Pair {
    Index a, b;
    double w;
  };
  auto pairs = [w](Index i, Index j, Pair* out) {
    if (i == j) {
      out[0] = {i, i, 1.0};
      return 1;
    }
    out[0] = {i, j, w};
    out[1] = {j, i, w};
    return 2;
  };
  Pair pp[2], qq[2];
  for (Index j = 0; j < k; ++j)
    for (Index i = 0; i <= j; ++i) {
      const int np_ = pairs(i, j, pp);
      const Index p = packed(i, j);
      for (Index l = 0; l < k; ++l)
        for (Index c = 0; c <= l; ++c) {
          const Index q = packed(c, l);
          if (q < p) continue;
          const int nq = pairs(c, l, qq);
          double h = 0.0;
          for (int x = 0; x < np_; ++x)
            for (int y = 0; y < nq; ++y) {
              const Index al = pp[x].a, be = pp[x].b, ga = qq[y].a, de = qq[y].b;
              double t = 0.0;
              for (int term = 0; term < terms; ++term) {
                t += (*Us[term])(be, ga) * (*Vs[term])(de, al) + (*Us[term])(de, al) * (*Vs[term])(be, ga);
              }
              h += pp[x].w * qq[y].w * t;
            }
          H(p, q) = h;
          H(q, p) = h;
        }
    }
}

}  // namespace spd_ml

namespace {

using namespace spd_ml;

// Fills p from X given as T = Q0^T X Q0 for an orthogonal Q0 in which X is nearly diagonal (the
// identity, or the previous iterate's eigenvectors); false when the eigensolver fails, X is not
// numerically positive definite, or f is not defined.
bool evaluate(const Problem& pr, MatrixXd T, const MatrixXd& Q0, Point& p) {
  const Index k = pr.data.n;
  p.Q = Q0;
  if (!jacobi_eigen(T, p.Q)) return false;
  p.lambda = T.diagonal();
  if (!(p.lambda.minCoeff() > static_cast<double>(k) * kEps * p.lambda.maxCoeff())) return false;
  p.V = p.Q;
  p.X.noalias() = p.V * p.lambda.asDiagonal() * p.V.transpose();
  p.X = symmetric_part(p.X);
  return criterion_at(pr, p);
}

// How a Newton run in the open cone ended.
enum class NewtonEnd { Failed, Converged, Stopped, Boundary, Unbounded };

// Newton's method on the positive definite n x n matrices X, from X0. On Boundary, `zero` marks
// the eigenvalues of cur (in cur.Q) heading to zero.
NewtonEnd newton_in_cone(const Problem& pr, double infinity, const MatrixXd& X0, int max_iterations, Point& cur,
                         double& gnorm, int& iterations, Eigen::Matrix<bool, Eigen::Dynamic, 1>& zero) {
  const DynamicReduction& data = pr.data;
  const Index n = data.n, k = n, np = k * (k + 1) / 2;
  const double root2 = std::sqrt(2.0);
  const double norm_a = data.R11.norm();
  const double data_scale = norm_a > 0.0 ? data.R12.norm() / norm_a : 0.0;

  iterations = 0;
  Point trial;
  if (!evaluate(pr, X0, MatrixXd::Identity(k, k), cur)) return NewtonEnd::Failed;

  Gradient d;
  Curvature cv;
  MatrixXd g, gS, H, Hmu, T;
  MatrixXd scaled[8];
  VectorXd grad(np), s(np), sqrt_lambda;
  Eigen::LLT<MatrixXd> llt(np);
  double radius = kInitialRadius;
  gnorm = 0.0;

  for (;;) {
    const VectorXd& lambda = cur.lambda;
    sqrt_lambda = lambda.cwiseSqrt();
    const MatrixXd& V = cur.V;
    gradient_at(pr, cur, d);
    // In X's eigenbasis, and the Riemannian gradient X^1/2 g X^1/2.
    g.noalias() = V.transpose() * d.gradX * V;
    g = symmetric_part(g);
    gS = sqrt_lambda.asDiagonal() * g * sqrt_lambda.asDiagonal();
    gnorm = gS.norm();

    // The boundary and the unbounded case, as in spd_tls_kernel.
    const double scale = std::max(lambda.maxCoeff(), data_scale);
    zero.resize(k);
    for (Index i = 0; i < k; ++i) zero(i) = lambda(i) <= kBoundaryRatio * scale && g(i, i) > 0.0;
    if (zero.any()) return NewtonEnd::Boundary;
    for (Index i = 0; i < k; ++i)
      if (lambda(i) >= infinity && g(i, i) < 0.0) return NewtonEnd::Unbounded;

    // The rounding level of gS: each term's rounding error from the sizes of what it cancels.
    {
      const MatrixXd termX = gradient_magnitude(pr, cur);
      const MatrixXd Vabs = V.cwiseAbs();
      const MatrixXd term = sqrt_lambda.asDiagonal() * (Vabs.transpose() * termX * Vabs) * sqrt_lambda.asDiagonal();
      const double floor = kRoundingMultiple * static_cast<double>(n) * kEps * term.norm();
      if (gnorm <= kGradientTolerance * cur.f || gnorm <= floor) return NewtonEnd::Converged;
    }
    if (iterations >= max_iterations || radius < kMinRadius) return NewtonEnd::Stopped;

    // The second derivative (curvature_at). With D = V Lambda^1/2 S Lambda^1/2 V^T and the
    // second-order term of X^1/2 exp(S) X^1/2, tr(gS S^2) / 2, the model's quadratic part is
    // sum_t tr(S U_t S V_t) over the four pairs below, each matrix taken to X's eigenbasis
    // and scaled by Lambda^1/2 on both sides.
    curvature_at(pr, cur, d, cv);
    auto to_eigenbasis = [&](const MatrixXd& A, MatrixXd& out, double factor) {
      out.noalias() = V.transpose() * A * V;
      out = factor * (sqrt_lambda.asDiagonal() * out * sqrt_lambda.asDiagonal());
    };
    to_eigenbasis(cur.K, scaled[0], 1.0);
    to_eigenbasis(cv.C1, scaled[1], 1.0);
    to_eigenbasis(d.F, scaled[2], 1.0);
    to_eigenbasis(cv.C2, scaled[3], 1.0);
    to_eigenbasis(cv.NK, scaled[4], 1.0);
    to_eigenbasis(cv.J, scaled[5], 2.0);
    scaled[6] = MatrixXd::Identity(k, k);
    scaled[7] = 0.5 * gS;
    const MatrixXd* const Us[4] = {&scaled[0], &scaled[2], &scaled[4], &scaled[6]};
    const MatrixXd* const Vs[4] = {&scaled[1], &scaled[3], &scaled[5], &scaled[7]};
    model_hessian(Us, Vs, 4, H);
    for (Index j = 0; j < k; ++j)
      for (Index i = 0; i <= j; ++i) grad(packed(i, j)) = i == j ? gS(i, i) : root2 * gS(i, j);

    // Levenberg-Marquardt shift, step, trust region and the step on the cone: as spd_tls_kernel.
    double step = 0.0, predicted = 0.0;
    if (!trust_region_step(H, grad, gnorm, radius, Hmu, llt, s, step, predicted)) return NewtonEnd::Failed;
    if (!cone_step(sqrt_lambda, s, step, T)) return NewtonEnd::Failed;
    ++iterations;

    const bool valid = evaluate(pr, T, cur.Q, trial);
    if (accept_trial(valid, cur.f, trial.f, predicted, step, n, radius)) std::swap(cur, trial);
  }
}

}  // namespace

double spd_ml_criterion(const DynamicReduction& data, const ScaledNoise& noise, const MatrixXd& X_s) {
  const Problem pr{data, noise, {}, data.R22.transpose() * data.R22};
  Point p;
  p.X = X_s;
  if (!criterion_at(pr, p)) return std::numeric_limits<double>::quiet_NaN();
  return p.f;
}

namespace {

// spd_ml_kernel with the eigenvalue beyond which f decreasing means no minimizer.
bool ml_kernel(const DynamicReduction& data, const ScaledNoise& noise, int max_iterations, const MatrixXd& X0_s,
               double infinity, SpdTlsKernel<Eigen::Dynamic>& out) {
  const Index n = data.n;
  const Problem pr{data, noise, data.R11.transpose() * data.R11, data.R22.transpose() * data.R22};
  Point cur;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> zero;
  double gnorm = 0.0;
  int iterations = 0;
  out.iterations = 0;
  NewtonEnd end = newton_in_cone(pr, infinity, X0_s, max_iterations, cur, gnorm, iterations, zero);
  out.iterations = iterations;
  if (end == NewtonEnd::Failed) return false;

  // On the boundary, the rank-r matrices from the iterate without the eigenvalues that left:
  // spd_ml_boundary turns their range too, and changes r, until the constrained problem's
  // first-order conditions hold.
  if (end == NewtonEnd::Boundary) {
    const Index kept = n - zero.count();
    MatrixXd V(n, n);
    VectorXd lambda(kept);
    for (Index i = 0, j = 0, z = kept; i < n; ++i) {
      if (zero(i)) {
        V.col(z++) = cur.V.col(i);
      } else {
        V.col(j) = cur.V.col(i);
        lambda(j++) = cur.lambda(i);
      }
    }
    if (!spd_ml_boundary(pr, infinity, max_iterations, std::move(V), std::move(lambda), out)) return false;
    out.criterion = spd_ml_criterion(data, noise, out.X_s);
    return true;
  }

  out.unbounded = end == NewtonEnd::Unbounded;
  out.boundary_zeros = 0;
  out.X_s = cur.X;
  out.criterion = spd_ml_criterion(data, noise, out.X_s);
  out.gradient_norm = gnorm;
  out.converged = end == NewtonEnd::Converged;
  return true;
}

// ||X|| <= ||A X|| / sigma_min(A) ~ ||R12|| / sigma_min(R11) for any fit worth the name.
double unbounded_threshold(const DynamicReduction& data) {
  const Index n = data.n;
  const double sigma_min = data.s_a.size() == n ? data.s_a(n - 1) : 0.0;
  return sigma_min > 0.0 ? kUnboundedRatio * data.R12.norm() / sigma_min : std::numeric_limits<double>::infinity();
}

}  // namespace

bool spd_ml_kernel(const DynamicReduction& data, const ScaledNoise& noise, int max_iterations, const MatrixXd& X0_s,
                   SpdTlsKernel<Eigen::Dynamic>& out) {
  return ml_kernel(data, noise, max_iterations, X0_s, unbounded_threshold(data), out);
}

bool spd_ml_solve(const DynamicReduction& data, const ScaledNoise& noise, int max_iterations,
                  SpdTlsKernel<Eigen::Dynamic>& out) {
  const Index n = data.n;
  int iterations = 0;
  // The kernel from X0 when it is positive definite (a Cholesky factorization here; the kernel
  // checks it to rounding) with a finite criterion.
  auto run = [&](const MatrixXd& X0) {
    const Eigen::LLT<MatrixXd> llt(X0);
    if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().array() > 0.0).all()) return false;
    if (!std::isfinite(spd_ml_criterion(data, noise, X0))) return false;
    // The iteration judges X by its own scale (positive definiteness, the boundary): in the data's
    // units X's entries can differ by many orders of magnitude (a column of A in mm, another in
    // m), so it runs in coordinates where the start has a unit diagonal, X = D X' D, by an exact
    // power-of-two congruence (the criterion is invariant: A' = A D, B' = B D^-1,
    // Sigma_A' = D Sigma_A D, Sigma_B' = D^-1 Sigma_B D^-1).
    VectorXd d(n);
    for (Index j = 0; j < n; ++j) d(j) = std::exp2(std::round(0.5 * std::log2(X0(j, j))));
    const VectorXd d_inv = d.cwiseInverse();
    DynamicReduction scaled;
    scaled.m = data.m;
    scaled.centred = data.centred;
    scaled.n = n;
    scaled.d = data.d;
    scaled.rank_a = data.rank_a;
    scaled.options = data.options;
    scaled.R11 = data.R11 * d.asDiagonal();
    scaled.R12 = data.R12 * d_inv.asDiagonal();
    scaled.R22 = data.R22 * d_inv.asDiagonal();
    ScaledNoise scaled_noise = noise;
    scaled_noise.cov_a = d.asDiagonal() * noise.cov_a * d.asDiagonal();
    scaled_noise.cov_b = d_inv.asDiagonal() * noise.cov_b * d_inv.asDiagonal();
    // X' = D^-1 X D^-1 has eigenvalues at most max(d^-2) times X's: the threshold of the unbounded
    // case moves with it (a bound, as the threshold itself).
    const double infinity = unbounded_threshold(data) * d_inv.cwiseAbs2().maxCoeff();
    const MatrixXd X0_scaled = d_inv.asDiagonal() * X0 * d_inv.asDiagonal();
    const bool solved = ml_kernel(scaled, scaled_noise, max_iterations, X0_scaled, infinity, out);
    iterations += out.iterations;
    if (solved) out.X_s = d.asDiagonal() * out.X_s * d.asDiagonal();
    return solved;
  };
  bool solved = false;
  if (data.rank_a == n) {
    MatrixXd X0;
    spde_kernel(data, X0);
    solved = run(X0);
  }
  if (!solved && noise.b_definite) {
    // Generalized TLS where SPDE is undefined or singular (A or B rank-deficient), or its run failed.
    GeneralizedTls gtls;
    generalized_tls(data, noise, gtls);
    MatrixXd X0;
    solved = gtls.exists && gtls.X_s.allFinite() &&
             nearest_spd_kernel<Eigen::Dynamic>(symmetric_part(gtls.X_s), EigenvalueFloor{}, X0) && run(X0);
  }
  out.iterations = iterations;
  return solved;
}

}  // namespace spdfit::detail
