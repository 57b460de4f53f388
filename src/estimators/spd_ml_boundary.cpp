#include "estimators/spd_ml_boundary.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "estimators/newton_common.hpp"
#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using namespace trust_region;
using namespace spd_ml;

namespace {

// Directions the multiplier may add to X's range over one run, in units of n: at a degenerate
// point (a multiplier with an eigenvalue 0, whose sign rounding decides) the rank could otherwise
// go up and down for ever.
constexpr Index kRankIncreasesPerColumn = 2;
// The line search along an added direction halves its step at most this often before deciding
// that the decrease the multiplier promised is below f's rounding.
constexpr int kLineSearchHalvings = 60;

// A point of the manifold of rank-r matrices: X = V_r diag(lambda) V_r^T with V = [V_r V_0]
// orthogonal (n x n, V_r its first r columns), and what f needs (p.X, p.G, p.E, p.K, p.f).
struct RankPoint {
  MatrixXd V;
  VectorXd lambda;
  Point p;
};

// Fills q.p from q.V and q.lambda; false when an eigenvalue is not numerically positive
// (lambda_min <= r eps lambda_max) or f is not defined.
bool evaluate(const Problem& pr, RankPoint& q) {
  const Index n = pr.data.n, r = q.lambda.size();
  if (r == 0) {
    q.p.X = MatrixXd::Zero(n, n);
  } else {
    if (!(q.lambda.minCoeff() > static_cast<double>(r) * kEps * q.lambda.maxCoeff())) return false;
    const auto Vr = q.V.leftCols(r);
    q.p.X.noalias() = Vr * q.lambda.asDiagonal() * Vr.transpose();
    q.p.X = symmetric_part(q.p.X);
  }
  return criterion_at(pr, q.p);
}

// The chart of the rank-r matrices at X = V diag(Lambda, 0) V^T: the step (S, T) (S symmetric
// r x r, T (n - r) x r) goes to V B Z B^T V^T with B = [Lambda^1/2; c T] and Z = exp(S), so that
// to first order dX = V Sigma St Sigma V^T with St = [S T^T; T 0] and Sigma = diag(Lambda^1/2, c I),
// and to second order V (Sigma St P St Sigma - [Lambda^1/2 S^2 Lambda^1/2 / 2, 0; 0, 0]) V^T,
// P = diag(I_r, 0). S moves the eigenvalues as the interior iteration does (X^1/2 exp(S) X^1/2);
// T turns the range into the null space, c^2 = lambda_max scaling it like the largest eigenvalue.
// Its coordinates are the packed ones of St (|s| = ||St||_F): the range's block in packed order,
// then the cross block.
struct Chart {
  Index n = 0, r = 0;
  std::vector<std::pair<Index, Index>> coordinates;  // (i, j), i <= j, of St
  VectorXd sigma;                                     // Sigma's diagonal
  double c2 = 0.0;

  Chart(Index n_, const VectorXd& lambda, double null_scale) : n(n_), r(lambda.size()) {
    for (Index j = 0; j < r; ++j)
      for (Index i = 0; i <= j; ++i) coordinates.emplace_back(i, j);
    for (Index i = 0; i < r; ++i)
      for (Index j = r; j < n; ++j) coordinates.emplace_back(i, j);
    c2 = r > 0 ? lambda.maxCoeff() : null_scale;
    sigma.resize(n);
    sigma.head(r) = lambda.cwiseSqrt();
    sigma.tail(n - r).setConstant(std::sqrt(c2));
  }
  Index size() const { return static_cast<Index>(coordinates.size()); }
  // The packed vector of a symmetric matrix in these coordinates (off-diagonal entries times sqrt 2).
  VectorXd packed_vector(const MatrixXd& M) const {
    VectorXd v(size());
    for (Index q = 0; q < size(); ++q) {
      const auto [i, j] = coordinates[static_cast<std::size_t>(q)];
      v(q) = i == j ? M(i, j) : std::sqrt(2.0) * M(i, j);
    }
    return v;
  }
  // Sigma V^T A V Sigma.
  MatrixXd scaled(const MatrixXd& V, const MatrixXd& A) const {
    MatrixXd out = V.transpose() * A * V;
    return sigma.asDiagonal() * out * sigma.asDiagonal();
  }
};

// How a Newton run on one rank ended.
enum class RankEnd { Failed, Converged, Stopped, Boundary, Unbounded };

// The rounding level of the chart's gradient, and of the multiplier's block (in the chart's
// scaling), from the magnitudes of grad f's terms.
void rounding_levels(const Problem& pr, const RankPoint& cur, const Chart& chart, double& gradient_floor,
                     double& multiplier_floor) {
  const Index n = pr.data.n, r = chart.r;
  const MatrixXd Vabs = cur.V.cwiseAbs();
  const MatrixXd term = chart.sigma.asDiagonal() * (Vabs.transpose() * gradient_magnitude(pr, cur.p) * Vabs) *
                        chart.sigma.asDiagonal();
  const double level = kRoundingMultiple * static_cast<double>(n) * kEps;
  gradient_floor = level * chart.packed_vector(term).norm();
  multiplier_floor = level * term.bottomRightCorner(n - r, n - r).norm();
}

// Newton's method on the matrices of rank r = cur.lambda.size() >= 1, a trust region in the chart
// above, re-centred at each accepted point. As the interior iteration: Boundary when eigenvalues
// head to zero while f decreases along them (`zero` marks them), Unbounded when one grows past
// `infinity` with f decreasing, Converged at the stopping rule, Stopped at the iteration limit.
RankEnd newton_on_rank(const Problem& pr, double infinity, int max_iterations, RankPoint& cur, double& gnorm,
                       int& iterations, Eigen::Matrix<bool, Eigen::Dynamic, 1>& zero) {
  const DynamicReduction& data = pr.data;
  const Index n = data.n, r = cur.lambda.size(), n0 = n - r;
  const double norm_a = data.R11.norm();
  const double data_scale = norm_a > 0.0 ? data.R12.norm() / norm_a : 0.0;
  const Index nr = r * (r + 1) / 2;

  iterations = 0;
  gnorm = 0.0;
  if (!evaluate(pr, cur)) return RankEnd::Failed;
  RankPoint trial;
  Gradient d;
  Curvature cv;
  MatrixXd Hfull, H, Hmu, Z, Tm, Bm;
  VectorXd s;
  Eigen::LLT<MatrixXd> llt;
  double radius = kInitialRadius;

  for (;;) {
    const Chart chart(n, cur.lambda, data_scale);
    const Index np = chart.size();
    gradient_at(pr, cur.p, d);
    const MatrixXd Gt = symmetric_part(MatrixXd(cur.V.transpose() * d.gradX * cur.V));
    const MatrixXd gS = chart.sigma.asDiagonal() * Gt * chart.sigma.asDiagonal();
    const VectorXd grad = chart.packed_vector(gS);
    gnorm = grad.norm();

    const double scale = std::max(cur.lambda.maxCoeff(), data_scale);
    zero.resize(r);
    for (Index i = 0; i < r; ++i) zero(i) = cur.lambda(i) <= kBoundaryRatio * scale && Gt(i, i) > 0.0;
    if (zero.any()) return RankEnd::Boundary;
    for (Index i = 0; i < r; ++i)
      if (cur.lambda(i) >= infinity && Gt(i, i) < 0.0) return RankEnd::Unbounded;

    double floor = 0.0, multiplier_floor = 0.0;
    rounding_levels(pr, cur, chart, floor, multiplier_floor);
    if (gnorm <= kGradientTolerance * cur.p.f || gnorm <= floor) return RankEnd::Converged;
    if (iterations >= max_iterations || radius < kMinRadius) return RankEnd::Stopped;

    // Newton's model in the chart: the second derivative of f (curvature_at) along
    // dX = Sigma St Sigma, sum_t tr(St U_t St V_t) over the pairs below, plus the chart's own
    // second-order term <Gt, Sigma St P St Sigma - ...> = tr(St P St (gS - P gS P / 2)); with
    // r = n this is the interior iteration's model.
    curvature_at(pr, cur.p, d, cv);
    MatrixXd scaled[8];
    scaled[0] = chart.scaled(cur.V, cur.p.K);
    scaled[1] = chart.scaled(cur.V, cv.C1);
    scaled[2] = chart.scaled(cur.V, d.F);
    scaled[3] = chart.scaled(cur.V, cv.C2);
    scaled[4] = chart.scaled(cur.V, cv.NK);
    scaled[5] = 2.0 * chart.scaled(cur.V, cv.J);
    scaled[6] = MatrixXd::Zero(n, n);
    scaled[6].topLeftCorner(r, r).setIdentity();
    scaled[7] = gS;
    scaled[7].topLeftCorner(r, r) *= 0.5;
    const MatrixXd* const Us[4] = {&scaled[0], &scaled[2], &scaled[4], &scaled[6]};
    const MatrixXd* const Vs[4] = {&scaled[1], &scaled[3], &scaled[5], &scaled[7]};
    model_hessian(Us, Vs, 4, Hfull);
    H.resize(np, np);
    for (Index q = 0; q < np; ++q)
      for (Index p = 0; p < np; ++p) {
        const auto [i, j] = chart.coordinates[static_cast<std::size_t>(p)];
        const auto [k, l] = chart.coordinates[static_cast<std::size_t>(q)];
        H(p, q) = Hfull(packed(i, j), packed(k, l));
      }

    double step = 0.0, predicted = 0.0;
    if (!trust_region_step(H, grad, gnorm, radius, Hmu, llt, s, step, predicted)) return RankEnd::Failed;
    ++iterations;
    // The trial point V B Z B^T V^T: B = Q_B R_B (Householder), so that its eigendecomposition is
    // that of the r x r R_B Z R_B^T in the first r columns of V Q_B.
    const VectorXd s_range = s.head(nr);
    if (!cone_step(VectorXd::Ones(r).eval(), s_range, step, Z)) return RankEnd::Failed;
    Tm.resize(n0, r);
    for (Index b = 0; b < r; ++b)
      for (Index a = 0; a < n0; ++a) Tm(a, b) = s(nr + b * n0 + a) / std::sqrt(2.0);
    Bm.resize(n, r);
    Bm.topRows(r) = chart.sigma.head(r).asDiagonal();
    Bm.bottomRows(n0) = std::sqrt(chart.c2) * Tm;
    const Eigen::HouseholderQR<MatrixXd> qr(Bm);
    const MatrixXd R = qr.matrixQR().topRows(r).triangularView<Eigen::Upper>();
    MatrixXd Y = symmetric_part(MatrixXd(R * Z * R.transpose()));
    MatrixXd W = MatrixXd::Identity(r, r);
    bool valid = jacobi_eigen(Y, W);
    if (valid) {
      trial.V = cur.V * MatrixXd(qr.householderQ());
      trial.V.leftCols(r) = (trial.V.leftCols(r) * W).eval();
      trial.lambda = Y.diagonal();
      valid = evaluate(pr, trial);
    }
    if (accept_trial(valid, cur.p.f, trial.p.f, predicted, step, n, radius)) std::swap(cur, trial);
  }
}

// X's range without the eigenvalues marked in `zero`: their eigenvectors join the null space.
void drop(RankPoint& cur, const Eigen::Matrix<bool, Eigen::Dynamic, 1>& zero) {
  const Index n = cur.V.rows(), r = cur.lambda.size(), kept = r - zero.count();
  MatrixXd V(n, n);
  VectorXd lambda(kept);
  Index j = 0, z = kept;
  for (Index i = 0; i < r; ++i) {
    if (zero(i)) {
      V.col(z++) = cur.V.col(i);
    } else {
      V.col(j) = cur.V.col(i);
      lambda(j++) = cur.lambda(i);
    }
  }
  V.rightCols(n - r) = cur.V.rightCols(n - r);
  cur.V = std::move(V);
  cur.lambda = std::move(lambda);
}

// The multiplier's test at a point where Newton converged on its rank: V_0^T grad f V_0 >= 0 to
// the stopping rule (in the chart's scaling, c^2 V_0^T grad f V_0 >= -max(1e-10 f, its rounding)).
// Where it fails, X grows along the eigenvector v of its smallest eigenvalue z < 0: to
// X + t v v^T with t minimizing f's second-order model along it (its curvature from curvature_at),
// halved until f decreases. Returns true when the rank grew; false when the conditions hold (or
// no step along v lowers f beyond rounding: then they hold to rounding).
bool grow(const Problem& pr, RankPoint& cur, bool& failed) {
  failed = false;
  const DynamicReduction& data = pr.data;
  const Index n = data.n, r = cur.lambda.size(), n0 = n - r;
  if (n0 == 0) return false;
  const double norm_a = data.R11.norm();
  const double data_scale = norm_a > 0.0 ? data.R12.norm() / norm_a : 0.0;
  const Chart chart(n, cur.lambda, data_scale);
  Gradient d;
  gradient_at(pr, cur.p, d);
  const MatrixXd V0 = cur.V.rightCols(n0);
  const MatrixXd G00 = symmetric_part(MatrixXd(V0.transpose() * d.gradX * V0));
  VectorXd mu;
  MatrixXd U;
  if (!symmetric_eigen(G00, mu, &U)) {
    failed = true;
    return false;
  }
  double floor = 0.0, multiplier_floor = 0.0;
  rounding_levels(pr, cur, chart, floor, multiplier_floor);
  if (chart.c2 * mu(0) >= -std::max(kGradientTolerance * cur.p.f, multiplier_floor)) return false;

  const VectorXd v = V0 * U.col(0);
  Curvature cv;
  curvature_at(pr, cur.p, d, cv);
  // d^2 f [v v^T, v v^T] = 2 ((v^T K v)(v^T C1 v) + (v^T F v)(v^T C2 v) + 2 (v^T L v)(v^T J v)).
  const double curvature = 2.0 * (v.dot(cur.p.K * v) * v.dot(cv.C1 * v) + v.dot(d.F * v) * v.dot(cv.C2 * v) +
                                  2.0 * v.dot(cv.NK * v) * v.dot(cv.J * v));
  double t = curvature > 0.0 ? -mu(0) / curvature : chart.c2;
  if (!(t > 0.0) || !std::isfinite(t)) t = chart.c2;
  RankPoint trial;
  trial.V.resize(n, n);
  trial.V.leftCols(r) = cur.V.leftCols(r);
  trial.V.col(r) = v;
  trial.V.rightCols(n0 - 1) = V0 * U.rightCols(n0 - 1);
  trial.lambda.resize(r + 1);
  trial.lambda.head(r) = cur.lambda;
  for (int halving = 0; halving < kLineSearchHalvings; ++halving, t *= 0.5) {
    trial.lambda(r) = t;
    if (evaluate(pr, trial) && trial.p.f < cur.p.f) {
      std::swap(cur, trial);
      return true;
    }
  }
  return false;
}

}  // namespace

bool spd_ml_boundary(const Problem& pr, double infinity, int max_iterations, MatrixXd V, VectorXd lambda,
                     SpdTlsKernel<Eigen::Dynamic>& out) {
  const Index n = pr.data.n;
  RankPoint cur{std::move(V), std::move(lambda), {}};
  Eigen::Matrix<bool, Eigen::Dynamic, 1> zero;
  double gnorm = 0.0;
  int iterations = 0;
  Index increases = 0;
  RankEnd end = RankEnd::Converged;
  for (;;) {
    if (cur.lambda.size() == 0) {
      // X = 0: no eigenvalue to move, only the multiplier to test. Where f is not defined there
      // (Sigma_B singular), 0 is the limit the iteration reached.
      if (!evaluate(pr, cur)) {
        out.X_s = MatrixXd::Zero(n, n);
        out.criterion = std::numeric_limits<double>::quiet_NaN();
        out.gradient_norm = 0.0;
        out.converged = true;
        out.boundary_zeros = n;
        return true;
      }
      end = RankEnd::Converged;
      gnorm = 0.0;
    } else {
      end = newton_on_rank(pr, infinity, max_iterations - out.iterations, cur, gnorm, iterations, zero);
      out.iterations += iterations;
      if (end == RankEnd::Failed) return false;
      if (end == RankEnd::Boundary) {
        drop(cur, zero);
        continue;
      }
    }
    if (end != RankEnd::Converged) break;
    if (increases >= kRankIncreasesPerColumn * n) {
      end = RankEnd::Stopped;
      break;
    }
    bool failed = false;
    const bool grew = grow(pr, cur, failed);
    if (failed) return false;
    if (!grew) break;
    ++increases;
    ++out.iterations;
  }
  out.unbounded = end == RankEnd::Unbounded;
  out.boundary_zeros = n - cur.lambda.size();
  out.X_s = cur.p.X;
  out.criterion = cur.p.f;
  out.gradient_norm = gnorm;
  out.converged = end == RankEnd::Converged;
  return true;
}

ScaledNoise equal_scaled_noise(Index n, double r2) {
  ScaledNoise noise;
  noise.cov_a = MatrixXd::Identity(n, n);
  noise.cov_b = r2 * MatrixXd::Identity(n, n);
  noise.a_definite = noise.b_definite = true;
  return noise;
}

BoundaryCertificate spd_ml_certificate(const DynamicReduction& data, const ScaledNoise& noise, const MatrixXd& X_s,
                                       Index rank) {
  const Index n = data.n;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BoundaryCertificate c;
  c.rank = rank;
  c.stationarity = c.cross_block = c.multiplier_min_eig = nan;
  const Problem pr{data, noise, {}, data.R22.transpose() * data.R22};
  Point p;
  p.X = X_s;
  if (!criterion_at(pr, p)) return c;
  Gradient d;
  gradient_at(pr, p, d);
  // The unit-diagonal coordinates: X^ = D^-1 X D^-1 and G^ = D G D, D = diag(X)^1/2, which a
  // change of units A -> A E, B -> B E^-1 (E diagonal) leaves alone. A zero diagonal entry (a
  // coordinate axis in the null space) keeps its unit.
  const double diagonal_floor = static_cast<double>(n) * kEps * X_s.diagonal().cwiseAbs().maxCoeff();
  VectorXd dd(n);
  for (Index j = 0; j < n; ++j) dd(j) = X_s(j, j) > diagonal_floor ? std::sqrt(X_s(j, j)) : 1.0;
  const MatrixXd Xh = symmetric_part(MatrixXd(dd.cwiseInverse().asDiagonal() * X_s * dd.cwiseInverse().asDiagonal()));
  const MatrixXd Gh = symmetric_part(MatrixXd(dd.asDiagonal() * d.gradX * dd.asDiagonal()));
  VectorXd w;
  MatrixXd Q;
  if (!symmetric_eigen(Xh, w, &Q)) return c;
  // Ascending: the null space first.
  const Index n0 = n - rank;
  const MatrixXd Vr = Q.rightCols(rank), V0 = Q.leftCols(n0);
  const VectorXd root = w.tail(rank).cwiseMax(0.0).cwiseSqrt();
  const double f = p.f > 0.0 ? p.f : 1.0;
  c.stationarity = (root.asDiagonal() * (Vr.transpose() * Gh * Vr) * root.asDiagonal()).norm() / f;
  c.cross_block = (root.asDiagonal() * (Vr.transpose() * Gh * V0)).norm() / f;
  VectorXd mu;
  if (n0 > 0 && symmetric_eigen(MatrixXd(symmetric_part(MatrixXd(V0.transpose() * Gh * V0))), mu)) {
    c.multiplier_min_eig = mu(0) / f;
  }
  return c;
}

}  // namespace spdfit::detail
