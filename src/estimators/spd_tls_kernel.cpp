#include "estimators/spd_tls_kernel.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Jacobi>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "estimators/newton_common.hpp"
#include "estimators/spd_ml_boundary.hpp"
#include "numerics/linalg.hpp"
#include "repair/nearest_spd_kernel.hpp"

namespace spdfit::detail {

using Eigen::Index;

using namespace trust_region;

namespace {

// A point of the iteration: X = Q diag(lambda) Q^T and what f needs, in the eigenbasis.
template <int MaxN>
struct Point {
  using Matrix = SquareMatrix<MaxN>;
  using Vector = typename BasicReduction<MaxN>::Vector;
  Matrix X, Q, Gt, R22t;  // X, its eigenvectors, (R11 X - R12) Q, R22 Q
  Vector lambda, k;       // eigenvalues ascending, k = 1 / (r^2 + lambda^2)
  double f = 0.0;
};

// Fills p from p.X, given T = Q0^T X Q0 for an orthogonal Q0 in which X is nearly diagonal (the
// identity, or the previous iterate's eigenvectors); false when the eigensolver fails or X is
// not numerically positive definite (unless allow_singular) or f is not finite.
template <int MaxN>
bool evaluate(const BasicReduction<MaxN>& data, double r2, SquareMatrix<MaxN> T, const SquareMatrix<MaxN>& Q0,
              Point<MaxN>& p, bool allow_singular = false) {
  using Matrix = SquareMatrix<MaxN>;
  const Index n = data.n;
  p.Q = Q0;
  if (!jacobi_eigen(T, p.Q)) return false;
  p.lambda = T.diagonal();
  if (!allow_singular && !(p.lambda.minCoeff() > static_cast<double>(n) * kEps * p.lambda.maxCoeff())) return false;
  const Matrix G = data.R11 * p.X - data.R12;
  p.Gt.noalias() = G * p.Q;
  p.R22t.noalias() = data.R22 * p.Q;
  p.k = (r2 + p.lambda.array().square()).inverse().matrix();
  // f = tr(Q^T E Q diag(k)) = sum_i k_i (||G q_i||^2 + ||R22 q_i||^2).
  p.f = (p.k.array() * (p.Gt.colwise().squaredNorm() + p.R22t.colwise().squaredNorm()).transpose().array()).sum();
  return std::isfinite(p.f);
}

}  // namespace

template <int MaxN>
double spd_tls_criterion(const BasicReduction<MaxN>& data, const SquareMatrix<MaxN>& X_s, double r_s) {
  Point<MaxN> p;
  p.X = X_s;
  const Index n = data.n;
  if (!evaluate<MaxN>(data, r_s * r_s, X_s, SquareMatrix<MaxN>::Identity(n, n), p, true)) return std::numeric_limits<double>::quiet_NaN();
  return p.f;
}

// How a Newton run ended.
enum class NewtonEnd { Failed, Converged, Stopped, Boundary, Unbounded };

namespace {

// The derivatives of f at a point, in the eigenbasis of its X.
template <int MaxN>
struct Derivatives {
  using Matrix = SquareMatrix<MaxN>;
  Matrix At, M, E, F;  // R11 Q, Q^T R11^T G Q, E = Gt^T Gt + R22t^T R22t, F = K E K
  Matrix g, gS;        // the Euclidean gradient and the Riemannian one, X^1/2 g X^1/2
  typename BasicReduction<MaxN>::Vector sqrt_lambda;
  double gnorm = 0.0;  // ||gS||_F
};

// The Euclidean gradient in the eigenbasis of X (K = diag(k) commutes with X = diag(lambda)):
// grad f = R11^T G K + K G^T R11 - X F - F X with F = K E K, so with M = Q^T R11^T G Q,
// g_ij = M_ij k_j + k_i M_ji - (lambda_i + lambda_j) F_ij; and the Riemannian gradient
// X^1/2 grad f X^1/2 (the derivative in S at S = 0).
template <int MaxN>
void gradient(const BasicReduction<MaxN>& data, const Point<MaxN>& cur, Derivatives<MaxN>& d) {
  const Index n = data.n;
  const auto& lambda = cur.lambda;
  const auto& k = cur.k;
  d.sqrt_lambda = lambda.cwiseSqrt();
  d.At.noalias() = data.R11 * cur.Q;
  d.M.noalias() = d.At.transpose() * cur.Gt;
  d.E.noalias() = cur.Gt.transpose() * cur.Gt;
  d.E.noalias() += cur.R22t.transpose() * cur.R22t;
  d.F = k.asDiagonal() * d.E * k.asDiagonal();
  d.g.resize(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) d.g(i, j) = d.M(i, j) * k(j) + k(i) * d.M(j, i) - (lambda(i) + lambda(j)) * d.F(i, j);
  d.gS = d.sqrt_lambda.asDiagonal() * d.g * d.sqrt_lambda.asDiagonal();
  d.gnorm = d.gS.norm();
}

// Where the iteration leaves the open cone: Boundary when an eigenvalue is driven towards zero
// while the criterion still decreases along it (g_ii > 0: its limit is 0, and the caller
// continues on the boundary without it; `zero` marks them), Unbounded when an eigenvalue grows past
// any sensible size while f still decreases along it (no minimizer); nothing otherwise.
template <int MaxN>
std::optional<NewtonEnd> leaves_the_cone(const Point<MaxN>& cur, const Derivatives<MaxN>& d, double data_scale,
                                         double infinity,
                                         Eigen::Matrix<bool, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1>& zero) {
  const auto& lambda = cur.lambda;
  const Index n = lambda.size();
  const double scale = std::max(lambda.maxCoeff(), data_scale);
  zero.resize(n);
  for (Index i = 0; i < n; ++i) zero(i) = lambda(i) <= kBoundaryRatio * scale && d.g(i, i) > 0.0;
  if (zero.any()) return NewtonEnd::Boundary;
  for (Index i = 0; i < n; ++i)
    if (lambda(i) >= infinity && d.g(i, i) < 0.0) return NewtonEnd::Unbounded;
  return std::nullopt;
}

// The rounding level of gS: each term's rounding error, from the sizes of what it cancels.
template <int MaxN>
double gradient_rounding_floor(const BasicReduction<MaxN>& data, const Point<MaxN>& cur, const Derivatives<MaxN>& d) {
  using Matrix = SquareMatrix<MaxN>;
  const Index n = data.n;
  const auto& lambda = cur.lambda;
  const auto& k = cur.k;
  const Matrix Gabs = (data.R11.cwiseAbs() * cur.X.cwiseAbs() + data.R12.cwiseAbs()) * cur.Q.cwiseAbs();
  const Matrix Mabs = d.At.cwiseAbs().transpose() * Gabs;
  const Matrix Eabs = cur.Gt.cwiseAbs().transpose() * Gabs;
  double floor2 = 0.0;
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) {
      const double t = d.sqrt_lambda(i) * d.sqrt_lambda(j) *
                       (Mabs(i, j) * k(j) + k(i) * Mabs(j, i) +
                        (lambda(i) + lambda(j)) * k(i) * k(j) * (Eabs(i, j) + Eabs(j, i)));
      floor2 += t * t;
    }
  return kRoundingMultiple * static_cast<double>(n) * kEps * std::sqrt(floor2);
}

// Newton's model of f(X^1/2 exp(S) X^1/2) in the symmetric S (eigenbasis):
// f + <gS, S> + sum_abc phi(a,b,c) S_ab S_bc with
// phi = sqrt(l_a l_c) (l_b h(a,b,c) + g_ac / 2), where f(X + D) = f + <g, D> +
// sum_abc h D_ab D_bc + O(D^3) and (K' the derivative of K, c_bc = (l_b + l_c) k_b k_c)
// h = k_b P_ac - (M_ac c_bc + M_ca c_ba) - F_ac + F_ac (l_a + l_b)(l_b + l_c) k_b.
// Coordinates: S_ii = s_ii, S_ij = S_ji = s_ij / sqrt(2), so that |s| = ||S||_F.
template <int MaxN, typename PMatrix, typename PVector>
void newton_model(const Point<MaxN>& cur, const Derivatives<MaxN>& d, PMatrix& H, PVector& grad) {
  using Matrix = SquareMatrix<MaxN>;
  const auto& lambda = cur.lambda;
  const auto& k = cur.k;
  const Index n = lambda.size();
  const double root2 = std::sqrt(2.0);
  const Matrix P = d.At.transpose() * d.At;
  H.setZero();
  for (Index b = 0; b < n; ++b)
    for (Index a = 0; a < n; ++a) {
      const double beta_ab = a == b ? 1.0 : 1.0 / root2;
      const Index pab = packed(a, b);
      for (Index c = 0; c < n; ++c) {
        const double beta_bc = b == c ? 1.0 : 1.0 / root2;
        const double c_bc = (lambda(b) + lambda(c)) * k(b) * k(c);
        const double c_ba = (lambda(b) + lambda(a)) * k(b) * k(a);
        const double h = k(b) * P(a, c) - (d.M(a, c) * c_bc + d.M(c, a) * c_ba) - d.F(a, c) +
                         d.F(a, c) * (lambda(a) + lambda(b)) * (lambda(b) + lambda(c)) * k(b);
        const double phi = d.sqrt_lambda(a) * d.sqrt_lambda(c) * (lambda(b) * h + 0.5 * d.g(a, c));
        H(pab, packed(b, c)) += phi * beta_ab * beta_bc;
      }
    }
  H = (H + H.transpose()).eval();
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i <= j; ++i) grad(packed(i, j)) = i == j ? d.gS(i, i) : root2 * d.gS(i, j);
}

}  // namespace

// Newton's method on the positive definite n x n matrices, a Riemannian trust region in the
// metric of the cone: at each iterate the gradient, the exits from the cone, the
// convergence test against the gradient's rounding level, Newton's model, its step within the
// region, the trial point on the cone, and the region's update. On Boundary, `zero` marks the
// eigenvalues of cur (in cur.Q) heading to zero.
template <int MaxN>
NewtonEnd newton(const BasicReduction<MaxN>& data, double r2, double infinity, const SquareMatrix<MaxN>& X0,
                 int max_iterations,
                 Point<MaxN>& cur, double& gnorm, int& iterations,
                 Eigen::Matrix<bool, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1>& zero) {
  using Matrix = SquareMatrix<MaxN>;
  constexpr int kMaxP = MaxN == Eigen::Dynamic ? Eigen::Dynamic : MaxN * (MaxN + 1) / 2;
  using PMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxP, kMaxP>;
  using PVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxP, 1>;
  const Index n = data.n, np = n * (n + 1) / 2;
  const double norm_a = data.R11.norm();
  const double data_scale = norm_a > 0.0 ? data.R12.norm() / norm_a : 0.0;

  iterations = 0;
  Point<MaxN> trial;
  cur.X = X0;
  if (!evaluate<MaxN>(data, r2, X0, Matrix::Identity(n, n), cur)) return NewtonEnd::Failed;

  Derivatives<MaxN> d;
  Matrix T;
  PMatrix H(np, np), Hmu(np, np);
  PVector grad(np), s(np);
  Eigen::LLT<PMatrix> llt(np);
  double radius = kInitialRadius;
  gnorm = 0.0;

  for (;;) {
    gradient(data, cur, d);
    gnorm = d.gnorm;
    if (auto end = leaves_the_cone(cur, d, data_scale, infinity, zero)) return *end;
    if (gnorm <= kGradientTolerance * cur.f || gnorm <= gradient_rounding_floor(data, cur, d)) {
      return NewtonEnd::Converged;
    }
    if (iterations >= max_iterations || radius < kMinRadius) return NewtonEnd::Stopped;

    newton_model(cur, d, H, grad);
    double step = 0.0, predicted = 0.0;
    if (!trust_region_step(H, grad, gnorm, radius, Hmu, llt, s, step, predicted)) return NewtonEnd::Failed;
    if (!cone_step(d.sqrt_lambda, s, step, T)) return NewtonEnd::Failed;
    trial.X.noalias() = cur.Q * T * cur.Q.transpose();
    trial.X = symmetric_part(trial.X);
    ++iterations;

    const bool valid = evaluate<MaxN>(data, r2, T, cur.Q, trial);
    if (accept_trial(valid, cur.f, trial.f, predicted, step, n, radius)) std::swap(cur, trial);
  }
}

namespace {

// On the boundary, in two stages. (1) The face: continue Newton on X = U Y U^T (U the
// eigenvectors whose eigenvalues stay, Y positive definite), where f(U Y U^T) is the same criterion
// for the data R11 U, R12 U, R22 U, from Y = the kept eigenvalues; and so on while eigenvalues keep
// leaving. An infimum at infinity on the face (an eigenvalue growing while f decreases) ends here:
// there is no minimizer. (2) The face's minimizer keeps the null space the iteration happened to
// have; the minimizer over all positive semidefinite matrices (the criterion is the likelihood
// criterion with Sigma_A = I, Sigma_B = r^2 I, spd_ml_kernel.hpp) is found by spd_ml_boundary from
// it, in dynamic matrices. Its answer replaces the face's only where its criterion is lower (it
// starts there and only descends, so a higher one means it failed): the estimate is never worse
// than the face's.
template <int MaxN>
bool boundary(const BasicReduction<MaxN>& data, double r2, double infinity, int max_iterations, Point<MaxN> cur,
              Eigen::Matrix<bool, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1> zero, double gnorm,
              SpdTlsKernel<MaxN>& out) {
  using Eigen::MatrixXd;
  using Matrix = SquareMatrix<MaxN>;
  const Index n = data.n;
  const double r_s = std::sqrt(r2);

  // (1) The face. U's columns and the directions that left (the null space) stay orthonormal.
  Matrix U = Matrix::Identity(n, n), null(n, 0);
  BasicReduction<MaxN> face;
  NewtonEnd end = NewtonEnd::Boundary;
  int iterations = 0;
  while (end == NewtonEnd::Boundary) {
    const Index k = U.cols(), kept = k - zero.count();
    Matrix U_next(n, kept), null_next(n, null.cols() + (k - kept)), Y0 = Matrix::Zero(kept, kept);
    null_next.leftCols(null.cols()) = null;
    for (Index i = 0, j = 0, z = null.cols(); i < k; ++i) {
      const auto u = (U * cur.Q.col(i)).eval();
      if (zero(i)) {
        null_next.col(z++) = u;
        continue;
      }
      U_next.col(j) = u;
      Y0(j, j) = cur.lambda(i);
      ++j;
    }
    U = U_next;
    null = null_next;
    if (kept == 0) break;
    face.n = kept;
    face.R11.noalias() = data.R11 * U;
    face.R12.noalias() = data.R12 * U;
    face.R22.noalias() = data.R22 * U;
    end = newton(face, r2, infinity, Y0, max_iterations - out.iterations, cur, gnorm, iterations, zero);
    out.iterations += iterations;
    if (end == NewtonEnd::Failed) return false;
  }
  out.unbounded = end == NewtonEnd::Unbounded;
  out.boundary_zeros = n - U.cols();
  if (U.cols() == 0) {
    out.X_s = Matrix::Zero(n, n);
    gnorm = 0.0;
    end = NewtonEnd::Converged;
  } else {
    out.X_s.noalias() = U * cur.X * U.transpose();
    out.X_s = symmetric_part(out.X_s);
  }
  out.criterion = spd_tls_criterion(data, out.X_s, r_s);
  out.gradient_norm = gnorm;
  out.converged = end == NewtonEnd::Converged;
  if (out.unbounded) return true;

  // (2) From the face's minimizer over the whole semidefinite cone.
  DynamicReduction dynamic;
  dynamic.m = data.m;
  dynamic.centred = data.centred;
  dynamic.n = n;
  dynamic.d = data.d;
  dynamic.R11 = data.R11;
  dynamic.R12 = data.R12;
  dynamic.R22 = data.R22;
  const ScaledNoise noise = equal_scaled_noise(n, r2);
  const spd_ml::Problem pr{dynamic, noise, dynamic.R11.transpose() * dynamic.R11,
                           dynamic.R22.transpose() * dynamic.R22};
  const Index kept = U.cols();
  MatrixXd V(n, n);
  Eigen::VectorXd lambda(kept);
  if (kept > 0) {
    V.leftCols(kept) = U * cur.Q;
    lambda = cur.lambda;
  }
  V.rightCols(n - kept) = null;
  SpdTlsKernel<Eigen::Dynamic> k;
  k.iterations = out.iterations;
  if (!spd_ml_boundary(pr, infinity, max_iterations, std::move(V), std::move(lambda), k)) return true;
  out.iterations = k.iterations;
  const Matrix X = k.X_s;
  const double criterion = spd_tls_criterion(data, X, r_s);
  if (k.unbounded || !(criterion <= out.criterion)) return true;
  out.X_s = X;
  out.boundary_zeros = k.boundary_zeros;
  out.criterion = criterion;
  out.gradient_norm = k.gradient_norm;
  out.converged = k.converged;
  return true;
}

}  // namespace

template <int MaxN>
bool spd_tls_kernel(const BasicReduction<MaxN>& data, double r_s, int max_iterations,
                    const SquareMatrix<MaxN>& X0_s, SpdTlsKernel<MaxN>& out) {
  const double r2 = r_s * r_s;
  const Index n = data.n;
  Point<MaxN> cur;
  Eigen::Matrix<bool, Eigen::Dynamic, 1, Eigen::ColMajor, MaxN, 1> zero;
  double gnorm = 0.0;
  int iterations = 0;
  out.iterations = 0;
  // ||X|| <= ||A X|| / sigma_min(A) ~ ||R12|| / sigma_min(R11) for any fit worth the name.
  const double sigma_min = data.s_a.size() == n ? data.s_a(n - 1) : 0.0;
  const double infinity = sigma_min > 0.0 ? kUnboundedRatio * data.R12.norm() / sigma_min
                                          : std::numeric_limits<double>::infinity();
  NewtonEnd end = newton(data, r2, infinity, X0_s, max_iterations, cur, gnorm, iterations, zero);
  out.iterations = iterations;
  if (end == NewtonEnd::Failed) return false;

  if (end == NewtonEnd::Boundary) return boundary(data, r2, infinity, max_iterations, cur, zero, gnorm, out);

  out.unbounded = end == NewtonEnd::Unbounded;
  out.boundary_zeros = 0;
  out.X_s = cur.X;
  out.criterion = spd_tls_criterion(data, out.X_s, r_s);
  out.gradient_norm = gnorm;
  out.converged = end == NewtonEnd::Converged;
  return true;
}

template <int MaxN>
bool spd_tls_solve(const BasicReduction<MaxN>& data, double r_s, int max_iterations, SpdTlsKernel<MaxN>& out) {
  SquareMatrix<MaxN> X0;
  int iterations = 0;
  out.iterations = 0;
  if (data.rank_a == data.n) {
    spde_kernel(data, X0);
    if (spd_tls_kernel(data, r_s, max_iterations, X0, out)) return true;
    iterations = out.iterations;
  }
  TlsKernel<MaxN> tls;
  tls_kernel(data, tls);
  const bool started = tls.exists && tls.X_s.allFinite() &&
                       nearest_spd_kernel<MaxN>(symmetric_part(tls.X_s), EigenvalueFloor{}, X0) &&
                       spd_tls_kernel(data, r_s, max_iterations, X0, out);
  out.iterations += iterations;
  return started;
}

#define SPDFIT_INSTANTIATE(MaxN)                                                                       \
  template double spd_tls_criterion<MaxN>(const BasicReduction<MaxN>&, const SquareMatrix<MaxN>&, double); \
  template bool spd_tls_kernel<MaxN>(const BasicReduction<MaxN>&, double, int, const SquareMatrix<MaxN>&,  \
                                     SpdTlsKernel<MaxN>&);                                     \
  template bool spd_tls_solve<MaxN>(const BasicReduction<MaxN>&, double, int, SpdTlsKernel<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace spdfit::detail
