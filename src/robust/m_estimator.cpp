// The robust fit: Huber's and Tukey's M-estimators of X by iteratively reweighted rows, Tukey's from a
// least-trimmed-squares start, and their bootstrap.
#include "robust/m_estimator.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <string>
#include <tuple>

#include <Eigen/Cholesky>

#include "factor/basic_reduction.hpp"
#include "factor/chunk_appender.hpp"
#include "factor/reduce.hpp"
#include "numerics/linalg.hpp"
#include "pipeline/offsets.hpp"
#include "pipeline/row_scores.hpp"
#include "pipeline/sentinels.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/random.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// The chi distribution's density with d degrees of freedom at u, less its log normalizer
// (0.5 d - 1) log 2 + log Gamma(d / 2), which the caller computes once; and a quadrature of E[f(u)].
double chi_density(double u, double d, double log_normalizer) {
  if (u <= 0.0) return d == 1.0 ? std::sqrt(2.0 / 3.14159265358979323846) : 0.0;
  return std::exp((d - 1.0) * std::log(u) - 0.5 * u * u - log_normalizer);
}

// Simpson's rule on [a, b] with `steps` (even) intervals of f(u) chi_density(u).
template <typename F>
double expectation(F f, double a, double b, double d, int steps = 2000) {
  if (!(b > a)) return 0.0;
  const double log_normalizer = (0.5 * d - 1.0) * std::log(2.0) + std::lgamma(0.5 * d);
  const double h = (b - a) / steps;
  double sum = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double u = a + i * h;
    const double weight = (i == 0 || i == steps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * f(u) * chi_density(u, d, log_normalizer);
  }
  return sum * h / 3.0;
}

// The upper end of the quadratures: the chi distribution's mass beyond is below 1e-30.
double upper_end(double d) { return std::sqrt(d) + 14.0; }

double efficiency(RobustLoss loss, double d, double k) {
  const double top = upper_end(d);
  if (loss == RobustLoss::Huber) {
    const double inside = expectation([](double) { return 1.0; }, 0.0, std::min(k, top), d);
    const double tail_inv = expectation([k](double u) { return k / u; }, std::min(k, top), top, d);
    const double tail_mass = expectation([](double) { return 1.0; }, std::min(k, top), top, d);
    const double squares = expectation([](double u) { return u * u; }, 0.0, std::min(k, top), d) + k * k * tail_mass;
    const double slope = inside + (1.0 - 1.0 / d) * tail_inv;
    return slope * slope / (squares / d);
  }
  const double end = std::min(k, top);
  const double w_mean = expectation(
      [k](double u) {
        const double t = 1.0 - (u / k) * (u / k);
        return t * t;
      },
      0.0, end, d);
  const double uw_mean = expectation(
      [k](double u) {
        const double t = 1.0 - (u / k) * (u / k);
        return -4.0 * u * u * t / (k * k);
      },
      0.0, end, d);
  const double squares = expectation(
      [k](double u) {
        const double t = 1.0 - (u / k) * (u / k);
        return t * t * t * t * u * u;
      },
      0.0, end, d);
  const double slope = w_mean + uw_mean / d;
  return slope * slope / (squares / d);
}

}  // namespace

double robust_tuning(RobustLoss loss, Index d, double target) {
  static std::mutex mutex;
  static std::map<std::tuple<int, Index, double>, double> known;
  const auto key = std::make_tuple(static_cast<int>(loss), d, target);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = known.find(key);
    if (it != known.end()) return it->second;
  }
  const double dd = static_cast<double>(std::max<Index>(d, 1));
  // Efficiency rises with k for both losses; bisection between a low and a high constant.
  double lo = loss == RobustLoss::Huber ? 1e-3 : 0.5, hi = loss == RobustLoss::Huber ? 20.0 + dd : 40.0 + dd;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (efficiency(loss, dd, mid) < target ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  const std::lock_guard<std::mutex> lock(mutex);
  known[key] = k;
  return k;
}

double chi_median(Index d) {
  // Computed once per d (60 bisection steps of a quadrature: milliseconds, against a robust
  // fit's few dozen at m = 1e5), as robust_tuning's constants are.
  static std::mutex mutex;
  static std::map<Index, double> known;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = known.find(d);
    if (it != known.end()) return it->second;
  }
  const double dd = static_cast<double>(std::max<Index>(d, 1));
  double lo = 0.0, hi = upper_end(dd);
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double cdf = expectation([](double) { return 1.0; }, 0.0, mid, dd);
    (cdf < 0.5 ? lo : hi) = mid;
  }
  const double median = 0.5 * (lo + hi);
  const std::lock_guard<std::mutex> lock(mutex);
  known[d] = median;
  return median;
}

double robust_weight(RobustLoss loss, double u, double k) {
  switch (loss) {
    case RobustLoss::None:
      return 1.0;
    case RobustLoss::Huber:
      return u <= k ? 1.0 : k / u;
    case RobustLoss::Tukey: {
      if (u >= k) return 0.0;
      const double t = 1.0 - (u / k) * (u / k);
      return t * t;
    }
  }
  return 1.0;
}

VectorXd robust_weights(RobustLoss loss, const VectorXd& u, double scale, double k) {
  VectorXd w;
  robust_weights_into(loss, u, scale, k, w);
  return w;
}

void robust_weights_into(RobustLoss loss, const VectorXd& u, double scale, double k, VectorXd& w) {
  const Index m = u.size();
  if (loss == RobustLoss::None) {
    w.setOnes(m);
    return;
  }
  if (!(scale > 0.0)) {
    w.setConstant(m, robust_weight(loss, 0.0, k));
    return;
  }
  // The operations of robust_weight on the same operands, so the same bits: t = u / scale, then
  // both of its branches for a block of rows and the one it takes, loops without branches that
  // vectorize (about half the rows are down-weighted at d = 3: a branch per row mispredicts at
  // that rate). No temporary array of m rows: its fresh pages cost more than the arithmetic.
  w = u / scale;
  double* t = w.data();
  constexpr Index kBlock = 256;
  double other[kBlock];
  for (Index i0 = 0; i0 < m; i0 += kBlock) {
    const Index r = std::min(kBlock, m - i0);
    double* ti = t + i0;
    if (loss == RobustLoss::Huber) {
      for (Index i = 0; i < r; ++i) other[i] = k / ti[i];
      for (Index i = 0; i < r; ++i) ti[i] = ti[i] <= k ? 1.0 : other[i];
    } else {
      for (Index i = 0; i < r; ++i) {
        const double x = 1.0 - (ti[i] / k) * (ti[i] / k);
        other[i] = x * x;
      }
      for (Index i = 0; i < r; ++i) ti[i] = ti[i] >= k ? 0.0 : other[i];
    }
  }
}

namespace {

// Rows at which least_squares_on accumulates the normal equations instead of factoring the rows:
// the concentration steps on all the rows fit half of them, where copying them costs more than the
// fit, and a start needs no more accuracy than the Gram matrix gives.
constexpr Index kNormalEquationRows = 256;

// The least-squares fit of B on [1 A] (intercept) or A over the rows `rows`: X, and c (empty without).
bool least_squares_on(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                      const std::vector<Index>& rows, bool intercept, MatrixXd& X, VectorXd& c) {
  const Index n = A.cols(), d = B.cols(), k = static_cast<Index>(rows.size());
  const Index p = n + (intercept ? 1 : 0);
  const auto gather = [&](Index first, Index count, MatrixXd& Z, MatrixXd& Y) {
    Z.resize(count, p);
    Y.resize(count, d);
    for (Index r = 0; r < count; ++r) {
      const Index i = rows[static_cast<std::size_t>(first + r)];
      if (intercept) Z(r, 0) = 1.0;
      Z.row(r).tail(n) = A.row(i);
      Y.row(r) = B.row(i);
    }
  };
  MatrixXd coef;
  if (k < kNormalEquationRows) {
    MatrixXd Z, Y;
    gather(0, k, Z, Y);
    const Eigen::ColPivHouseholderQR<MatrixXd> qr(Z);
    if (qr.rank() < p) return false;
    coef = qr.solve(Y);
  } else {
    // The normal equations, a block of rows at a time.
    MatrixXd G = MatrixXd::Zero(p, p), H = MatrixXd::Zero(p, d), Z, Y;
    for (Index first = 0; first < k; first += kNormalEquationRows) {
      gather(first, std::min(kNormalEquationRows, k - first), Z, Y);
      G.noalias() += Z.transpose().lazyProduct(Z);  // p, d small: coefficient-wise beats a GEMM
      H.noalias() += Z.transpose().lazyProduct(Y);
    }
    const Eigen::ColPivHouseholderQR<MatrixXd> qr(G);
    if (qr.rank() < p) return false;
    coef = qr.solve(H);
  }
  if (!coef.allFinite()) return false;
  X = coef.bottomRows(n);
  c = intercept ? VectorXd(coef.row(0).transpose()) : VectorXd();
  return true;
}

// The h rows of least whitened residual (ascending row order; ties at the h-th value broken by
// row), their sum of squares.
double trimmed(const VectorXd& u, Index h, std::vector<Index>& rows) {
  std::vector<double> values(u.data(), u.data() + u.size());
  std::nth_element(values.begin(), values.begin() + (h - 1), values.end());
  const double cut = values[static_cast<std::size_t>(h - 1)];
  Index below = 0;
  for (Index i = 0; i < u.size(); ++i) below += u(i) < cut;
  Index ties = h - below;  // rows at exactly `cut` to take, the first ones
  rows.clear();
  rows.reserve(static_cast<std::size_t>(h));
  double sum = 0.0;
  for (Index i = 0; i < u.size(); ++i) {
    if (u(i) < cut || (u(i) == cut && ties-- > 0)) {
      rows.push_back(i);
      sum += u(i) * u(i);
    }
  }
  return sum;
}

struct Candidate {
  MatrixXd X;
  VectorXd c;
  double objective = std::numeric_limits<double>::infinity();
};

// Concentration steps (C-steps) on the rows of A, B: refit on the h rows of least residual until the
// trimmed sum stops falling (at most `steps`).
void concentrate(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, bool intercept,
                 Method method, const FitOptions& options, Index h, int steps, Candidate& cand) {
  std::vector<Index> rows;
  for (int s = 0; s < steps; ++s) {
    const VectorXd u = whitened_residuals(A, B, cand.X, cand.c, residual_covariance(cand.X, method, options));
    const double objective = trimmed(u, h, rows);
    if (!(objective < cand.objective * (1.0 - 1e-12)) && s > 0) {
      cand.objective = std::min(cand.objective, objective);
      return;
    }
    cand.objective = objective;
    MatrixXd X;
    VectorXd c;
    if (!least_squares_on(A, B, rows, intercept, X, c)) return;
    cand.X = X;
    cand.c = c;
  }
  const VectorXd u = whitened_residuals(A, B, cand.X, cand.c, residual_covariance(cand.X, method, options));
  cand.objective = trimmed(u, h, rows);
}

// Elemental starts: this many random subsets of p rows, each concentrated twice on a subsample.
constexpr int kElementalStarts = 500;
constexpr Index kSubsampleRows = 1500;
constexpr int kBestStarts = 5;
// Of those, the best few are concentrated on all the rows (each step a pass over every row).
constexpr std::size_t kFullDataStarts = 2;
constexpr int kFullDataSteps = 10;

}  // namespace

TrimmedStart least_trimmed_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                   bool intercept, Method method, const FitOptions& options) {
  const Index m = A.rows(), n = A.cols(), d = B.cols();
  const Index p = n + (intercept ? 1 : 0);
  const Index h = std::min(m, (m + p + 1) / 2);
  Random random(trial_seed(0x4c5453, static_cast<std::uint64_t>(m)));  // "LTS": a fixed seed
  // The subsample the elemental starts are judged on.
  std::vector<Index> sub(static_cast<std::size_t>(m));
  std::iota(sub.begin(), sub.end(), Index{0});
  if (m > kSubsampleRows) {
    for (Index i = 0; i < kSubsampleRows; ++i) {
      const Index j = i + std::min(static_cast<Index>(random.uniform() * static_cast<double>(m - i)), m - i - 1);
      std::swap(sub[static_cast<std::size_t>(i)], sub[static_cast<std::size_t>(j)]);
    }
    sub.resize(static_cast<std::size_t>(kSubsampleRows));
    std::sort(sub.begin(), sub.end());
  }
  const Index ms = static_cast<Index>(sub.size());
  MatrixXd As(ms, n), Bs(ms, d);
  for (Index r = 0; r < ms; ++r) {
    As.row(r) = A.row(sub[static_cast<std::size_t>(r)]);
    Bs.row(r) = B.row(sub[static_cast<std::size_t>(r)]);
  }
  const Index hs = std::min(ms, (ms + p + 1) / 2);
  std::vector<Candidate> best;
  std::vector<Index> elemental(static_cast<std::size_t>(p));
  // Elemental subsets need more rows than parameters (else the least-squares start on all rows).
  const int starts = ms > p ? kElementalStarts : 0;
  for (int t = 0; t < starts; ++t) {
    // p distinct rows of the subsample.
    for (Index k = 0; k < p; ++k) {
      Index pick;
      do {
        pick = std::min(static_cast<Index>(random.uniform() * static_cast<double>(ms)), ms - 1);
      } while (std::find(elemental.begin(), elemental.begin() + k, pick) != elemental.begin() + k);
      elemental[static_cast<std::size_t>(k)] = pick;
    }
    Candidate cand;
    if (!least_squares_on(As, Bs, elemental, intercept, cand.X, cand.c)) continue;
    concentrate(As, Bs, intercept, method, options, hs, 2, cand);
    if (!std::isfinite(cand.objective)) continue;
    best.push_back(std::move(cand));
    std::sort(best.begin(), best.end(), [](const Candidate& a, const Candidate& b) { return a.objective < b.objective; });
    if (best.size() > static_cast<std::size_t>(kBestStarts)) best.pop_back();
  }
  TrimmedStart out;
  if (best.empty()) {
    // No elemental subset of full rank (a design of few distinct rows): least squares on all rows.
    std::vector<Index> all(static_cast<std::size_t>(m));
    std::iota(all.begin(), all.end(), Index{0});
    if (!least_squares_on(A, B, all, intercept, out.X, out.c)) {
      out.X = MatrixXd::Zero(n, d);
      if (intercept) out.c = VectorXd::Zero(d);
    }
  } else {
    // The best starts concentrated on all the rows.
    Candidate winner;
    if (best.size() > kFullDataStarts) best.resize(kFullDataStarts);
    for (Candidate& cand : best) {
      cand.objective = std::numeric_limits<double>::infinity();
      concentrate(A, B, intercept, method, options, h, m > ms ? kFullDataSteps : 20, cand);
      if (cand.objective < winner.objective) winner = cand;
    }
    out.X = winner.X;
    out.c = winner.c;
  }
  const VectorXd u = whitened_residuals(A, B, out.X, out.c, residual_covariance(out.X, method, options));
  out.scale = median(std::vector<double>(u.data(), u.data() + u.size())) / chi_median(d);
  return out;
}

// A pass counts the values below the bracket and gathers those in it; the selection is among those
// only when the middle ranks fall in the bracket, else among all values (median()).
double median_near(const VectorXd& u, const VectorXd& counts, double guess, std::vector<double>& bracket) {
  const Index m = u.size();
  const auto counted = [&counts](Index i) { return counts.size() == 0 || counts(i) > 0; };
  if (guess > 0.0 && std::isfinite(guess)) {
    const double lo = 0.9 * guess, hi = 1.1 * guess;
    Index below = 0, total = 0, size = 0;
    // Without branches on the values (about a third of them fall on either side of a bound, which
    // no branch predictor guesses): every value is written, and kept by the count's increment.
    if (bracket.size() < static_cast<std::size_t>(m)) bracket.resize(static_cast<std::size_t>(m));
    for (Index i = 0; i < m; ++i) {
      const double v = u(i);
      const Index take = counted(i) ? 1 : 0;
      total += take;
      below += take & static_cast<Index>(v < lo);
      bracket[static_cast<std::size_t>(size)] = v;
      size += take & static_cast<Index>(v >= lo) & static_cast<Index>(v <= hi);  // &, not &&: no branch
    }
    // 0-based ranks k (and k - 1 for an even count) must fall in the bracket.
    const Index k = total / 2, first = total % 2 == 1 ? k : k - 1;
    if (total > 0 && first >= below && k < below + size) {
      const auto begin = bracket.begin(), end = begin + static_cast<std::ptrdiff_t>(size);
      const auto at = begin + static_cast<std::ptrdiff_t>(k - below);
      std::nth_element(begin, at, end);
      const double upper = *at;
      if (total % 2 == 1) return upper;
      return 0.5 * (upper + *std::max_element(begin, at));
    }
  }
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(m));
  for (Index i = 0; i < m; ++i) {
    if (counted(i)) values.push_back(u(i));
  }
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  return median(std::move(values));
}

namespace {

// Rows per block of gram_factor's passes: the blocks' copies stay in cache, and no pass allocates
// a matrix of m rows (whose fresh pages cost more than the arithmetic at these widths).
constexpr Index kGramBlockRows = 2048;

// Rows [i0, i0 + r) of [A B] scaled exactly by 2^-[ea eb], into Z, less `shift` when it is given.
void scaled_rows(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Index i0, Index r, int ea,
                 int eb, const Eigen::RowVectorXd& shift, MatrixXd& Z) {
  const Index n = A.cols(), d = B.cols();
  Z.resize(r, n + d);
  Z.leftCols(n) = A.middleRows(i0, r);
  Z.rightCols(d) = B.middleRows(i0, r);
  auto left = Z.leftCols(n);
  auto right = Z.rightCols(d);
  multiply_by_power_of_two(left, -ea);
  multiply_by_power_of_two(right, -eb);
  if (shift.size() == n + d) Z.rowwise() -= shift;
}

// The rows of positive weight and the weights' sum; false when too few rows (at most n + d) or no
// mass remain for a factor.
bool weight_totals(const VectorXd& w, Index columns, Index& rows, double& mass) {
  // Eigen's reductions (vectorized, several partial sums): a loop's one chain of dependent
  // additions took a quarter of the downdate's time.
  rows = (w.array() > 0.0).count();
  mass = w.sum();
  return rows > columns && mass > 0.0;
}

// The factor of a Gram matrix G (the full p x p, symmetric) of rows scaled by 2^-[ea eb]: its
// Cholesky factor, or nothing where that breaks down (the caller uses the QR).
std::optional<TriangularFactor> factor_of_gram(const MatrixXd& G, Index n, Index rows, int ea, int eb, bool intercept,
                                               const VectorXd& means, double mass) {
  const Eigen::LLT<MatrixXd> llt(G);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const MatrixXd R = llt.matrixU();
  if (!R.allFinite()) return std::nullopt;
  return ChunkAppender::from_triangle(R, n, rows, ea, eb, intercept, means, mass);
}

// sum_i w_i (z_i - shift)^T (z_i - shift) over the rows z_i of [A B] 2^-[ea eb], a block of rows at
// a time (the full symmetric matrix).
MatrixXd weighted_gram(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const VectorXd& w,
                       int ea, int eb, const Eigen::RowVectorXd& shift = {}) {
  const Index m = A.rows(), p = A.cols() + B.cols();
  MatrixXd G = MatrixXd::Zero(p, p), Z;
  for (Index i0 = 0; i0 < m; i0 += kGramBlockRows) {
    const Index r = std::min(kGramBlockRows, m - i0);
    scaled_rows(A, B, i0, r, ea, eb, shift, Z);
    Z.array().colwise() *= w.segment(i0, r).array().sqrt();
    G.selfadjointView<Eigen::Lower>().rankUpdate(Z.transpose());
  }
  return G.selfadjointView<Eigen::Lower>();
}

// The factor of the rows of [A B] weighted by w (with an intercept, about their weighted means) from
// the weighted Gram matrix and its Cholesky factor: for the reweighting's inner iterations, which
// need X only to the accuracy at which the weights settle, at a fraction of a QR's cost (one
// symmetric rank-k product on the BLAS). The Gram matrix squares the condition number, so the
// converged weights are fitted once more by the QR (TriangularFactor::append), and a Cholesky that
// breaks down (A ill-conditioned beyond about 1e7) gives nothing: the caller uses the QR.
std::optional<TriangularFactor> gram_factor(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                            const VectorXd& w, bool intercept, int ea, int eb) {
  const Index m = A.rows(), n = A.cols(), d = B.cols(), p = n + d;
  Index rows = 0;
  double mass = 0.0;
  if (!weight_totals(w, p, rows, mass)) return std::nullopt;
  Eigen::RowVectorXd mu;
  VectorXd means;
  if (intercept) {
    // The weighted means in two passes: the second takes what rounding left of the first.
    MatrixXd Z;
    const auto weighted_sum = [&](const Eigen::RowVectorXd& shift) {
      Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(p);
      for (Index i0 = 0; i0 < m; i0 += kGramBlockRows) {
        const Index r = std::min(kGramBlockRows, m - i0);
        scaled_rows(A, B, i0, r, ea, eb, shift, Z);
        sum.noalias() += w.segment(i0, r).transpose() * Z;
      }
      return sum;
    };
    mu = weighted_sum(Eigen::RowVectorXd()) / mass;
    mu += weighted_sum(mu) / mass;
    means = mu.transpose();
    means.head(n) = times_power_of_two(VectorXd(means.head(n)), ea);
    means.tail(d) = times_power_of_two(VectorXd(means.tail(d)), eb);
  }
  return factor_of_gram(weighted_gram(A, B, w, ea, eb, mu), n, rows, ea, eb, intercept, means, mass);
}

// Huber's weights are 1 but for the rows of large residual: the weighted Gram matrix (without an
// intercept) is the unweighted one less sum (1 - w_i) z_i z_i^T over those rows, which costs a
// pass over them only. A row far larger than the others (a logger's 1e30, which Huber
// down-weights to nearly 0) would leave only rounding of itself in that difference: such rows stay
// out of the unweighted matrix and are added with their weight instead.
struct GramBase {
  MatrixXd G;              // of the rows not `large`, scaled by 2^-[ea eb]
  std::vector<char> large;  // per row: squared norm above kLargeRowRatio times the median's
};
constexpr double kLargeRowRatio = 1e6;

GramBase gram_base(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, int ea, int eb) {
  const Index m = A.rows();
  VectorXd norms(m);
  MatrixXd Z;
  for (Index i0 = 0; i0 < m; i0 += kGramBlockRows) {
    const Index r = std::min(kGramBlockRows, m - i0);
    scaled_rows(A, B, i0, r, ea, eb, {}, Z);
    norms.segment(i0, r) = Z.rowwise().squaredNorm();
  }
  const double typical = median(std::vector<double>(norms.data(), norms.data() + m));
  VectorXd w = VectorXd::Ones(m);
  GramBase base;
  base.large.assign(static_cast<std::size_t>(m), 0);
  for (Index i = 0; i < m; ++i) {
    if (!(norms(i) <= kLargeRowRatio * typical)) {
      base.large[static_cast<std::size_t>(i)] = 1;
      w(i) = 0.0;
    }
  }
  base.G = weighted_gram(A, B, w, ea, eb);
  return base;
}

// gram_factor without an intercept from `base`: the rows of weight below 1 taken out (the large
// ones added with their weight), a block of them at a time.
std::optional<TriangularFactor> downdated_gram_factor(const Eigen::Ref<const MatrixXd>& A,
                                                      const Eigen::Ref<const MatrixXd>& B, const VectorXd& w,
                                                      const GramBase& base, int ea, int eb) {
  const Index m = A.rows(), n = A.cols(), p = n + B.cols();
  Index rows = 0;
  double mass = 0.0;
  if (!weight_totals(w, p, rows, mass)) return std::nullopt;
  MatrixXd G = base.G, D(kGramBlockRows, p), z;
  Index k[2] = {0, 0};  // rows gathered: taken out (0), added (1)
  MatrixXd E(kGramBlockRows, p);
  const auto flush = [&](int which) {
    if (k[which] == 0) return;
    MatrixXd& rows_of = which == 0 ? D : E;
    G.selfadjointView<Eigen::Lower>().rankUpdate(rows_of.topRows(k[which]).transpose(), which == 0 ? -1.0 : 1.0);
    k[which] = 0;
  };
  // Each row scaled by 2^-[ea eb] times its root weight in one product: exactly scaled_rows' value
  // (a power of two commutes with rounding) while root 2^-e stays a normal double, without its
  // per-row copies (a pass over every down-weighted row at each iteration).
  const bool normal = std::abs(ea) <= 1000 && std::abs(eb) <= 1000;
  const double sa = normal ? std::ldexp(1.0, -ea) : 0.0, sb = normal ? std::ldexp(1.0, -eb) : 0.0;
  const Index d = B.cols();
  for (Index i = 0; i < m; ++i) {
    const bool large = base.large[static_cast<std::size_t>(i)] != 0;
    if (!large && w(i) >= 1.0) continue;
    const int which = large ? 1 : 0;
    MatrixXd& target = which == 0 ? D : E;
    const double root = std::sqrt(large ? w(i) : 1.0 - w(i));  // >= 1e-8 for the rows not large
    if (normal && !large) {
      target.row(k[which]).head(n) = (root * sa) * A.row(i);
      target.row(k[which]).tail(d) = (root * sb) * B.row(i);
    } else {
      scaled_rows(A, B, i, 1, ea, eb, {}, z);
      target.row(k[which]) = root * z.row(0);
    }
    if (++k[which] == kGramBlockRows) flush(which);
  }
  flush(0);
  flush(1);
  G = G.selfadjointView<Eigen::Lower>();
  return factor_of_gram(G, n, rows, ea, eb, false, VectorXd(), mass);
}

// One robust fit's iterations, from X (and c) with the scale `scale` (Huber: re-estimated each
// iteration). [ea eb]: the data's scale exponents (TriangularFactor's own rule), for the Gram
// matrices of every iteration. `counts` (empty: 1) multiply the weights (a bootstrap resample).
// `base` (Huber without an intercept or counts; else null): the unweighted Gram matrix the inner
// fits downdate.
struct Iterated {
  FitResult result;
  VectorXd weights;
  VectorXd c;
  double scale = 0.0;
  int iterations = 0;
  bool converged = false;
  std::optional<TriangularFactor> factor;
  Reduction data;
};

Iterated iterate(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Method method,
                 const FitOptions& inner, bool intercept, RobustLoss loss, double k, MatrixXd X, VectorXd c,
                 double scale, int ea, int eb, const VectorXd& counts, int max_iterations,
                 const GramBase* base = nullptr) {
  Iterated out;
  const Index d = B.cols();
  const double median_chi = chi_median(d);
  std::vector<double> bracket;
  VectorXd u, w;  // each iteration's, in the same storage (fresh pages cost more than their arithmetic)
  for (int it = 1; it <= max_iterations; ++it) {
    whitened_residuals_into(A, B, X, c, residual_covariance(X, method, inner), u);
    if (loss == RobustLoss::Huber) {
      const double next = median_near(u, counts, scale * median_chi, bracket);
      if (!std::isnan(next)) scale = next / median_chi;  // NaN: no rows
    }
    robust_weights_into(loss, u, scale, k, w);
    if (counts.size()) w.array() *= counts.array();
    // The weighted fit: from the Gram matrix while the weights settle, by the QR for the last.
    const auto weighted_fit = [&](bool by_gram, std::optional<TriangularFactor>& factor, Reduction& data) {
      factor.reset();
      if (by_gram) factor = base ? downdated_gram_factor(A, B, w, *base, ea, eb) : gram_factor(A, B, w, intercept, ea, eb);
      if (!factor) {
        factor.emplace(A.cols(), B.cols(), intercept);
        factor->append(A, B, w);
      }
      FitOptions step = inner;
      if (by_gram) step.diagnostics = false;
      data = reduce_for(*factor, step, method);
      FitResult fitted = fit(data, method);
      // auto chooses among the methods that weigh rows: never spde, whose criterion has no rows.
      if (method == Method::Auto && fitted.diagnostics.chosen_method == Method::Spde) {
        fitted = fit(data, Method::SpdTotalLeastSquares);
      }
      return fitted;
    };
    std::optional<TriangularFactor> factor;
    Reduction data;
    FitResult fitted = weighted_fit(true, factor, data);
    const double step_change = fitted.ok() ? (fitted.X - X).norm() : 0.0;
    const double step_size = fitted.ok() ? std::max(fitted.X.norm(), std::numeric_limits<double>::min()) : 1.0;
    // The weights have settled (X moves by less than 1e-8 of itself, far below its standard errors,
    // or the iterations are spent): the last fit by the QR, with every diagnostic.
    constexpr double kSettledGram = 1e-8;
    const bool last = !fitted.ok() || step_change <= kSettledGram * step_size || scale == 0.0 || it == max_iterations;
    if (last) fitted = weighted_fit(false, factor, data);
    out.iterations = it;
    out.weights.swap(w);  // w keeps the other buffer for the next iteration
    out.scale = scale;
    if (!fitted.ok() || !fitted.X.allFinite()) {
      out.result = std::move(fitted);
      out.factor = std::move(factor);
      out.data = data;
      return out;
    }
    X = fitted.X;
    c = intercept_offsets(*factor, X);
    out.result = std::move(fitted);
    out.factor = std::move(factor);
    out.data = data;
    out.c = c;
    if (last) {
      out.converged = it < max_iterations || step_change <= kSettledGram * step_size || scale == 0.0;
      break;
    }
  }
  return out;
}

}  // namespace

namespace {

// 1 for each row of A and B, 0 for one holding a value of magnitude kSentinelMagnitude or more;
// empty when no row does.
VectorXd valid_rows(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B) {
  const std::vector<Index> codes = sentinel_rows(A, B);
  if (codes.empty()) return {};
  VectorXd out = VectorXd::Ones(A.rows());
  for (Index i : codes) out(i) = 0.0;
  return out;
}

}  // namespace

RobustReport robust_report(RobustLoss loss, double k, const VectorXd& weights, double scale, int iterations,
                           bool converged) {
  constexpr double kDownweighted = 0.5;
  constexpr std::size_t kListedRows = 1000;
  RobustReport report;
  report.method = loss;
  report.tuning = k;
  report.iterations = iterations;
  report.converged = converged;
  report.scale = scale;
  report.weights_min = weights.size() ? weights.minCoeff() : 1.0;
  for (Index i = 0; i < weights.size(); ++i) {
    if (weights(i) < kDownweighted) {
      ++report.rows_downweighted_count;
      if (report.rows_downweighted.size() < kListedRows) report.rows_downweighted.push_back(static_cast<std::uint64_t>(i) + 1);
    }
  }
  return report;
}

RobustFit robust_fit(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Method method,
                     const FitOptions& options) {
  if (!robust_applies(method)) {
    throw OptionError("`robust` weighs the rows, and spde's area criterion is not a sum over rows: use auto, spd-tls or "
                      "another method with `robust`",
                      Code::OptionConflict, "robust");
  }
  const Index m = A.rows(), d = B.cols();
  const RobustLoss loss = options.robust;
  const double k = options.robust_tuning ? *options.robust_tuning : robust_tuning(loss, d);
  const bool intercept = options.offsets == Offsets::Estimate;
  FitOptions inner = options;
  inner.bootstrap = 0;
  inner.robust = RobustLoss::None;
  inner.robust_tuning.reset();
  MatrixXd X;
  VectorXd c;
  double scale = 0.0;
  // The data's scale exponents, for every Gram matrix; Huber without an intercept: the unweighted
  // Gram matrix once, for the start and for every iteration's fit (downdated by the rows weighted
  // below 1).
  const int ea = scale_exponent(A).value_or(0), eb = scale_exponent(B).value_or(0);
  // Rows holding a logger's code for an invalid reading (kSentinelMagnitude) are not measurements:
  // weight 0 throughout, for both losses. (Huber's weight k/u leaves a row's influence growing
  // with its values in A: with 9.9e37 in A it decided X.) Empty when there is none.
  const VectorXd valid = valid_rows(A, B);
  std::optional<GramBase> base;
  if (loss == RobustLoss::Huber && !intercept) base = gram_base(A, B, ea, eb);
  // Least trimmed squares' start, of the valid rows only (its random subsets those of the data
  // without the logger's codes).
  const auto trimmed_start = [&] {
    if (!valid.size()) return least_trimmed_squares(A, B, intercept, method, inner);
    std::vector<Index> rows;
    for (Index i = 0; i < m; ++i) {
      if (valid(i) > 0.0) rows.push_back(i);
    }
    return least_trimmed_squares(MatrixXd(A(rows, Eigen::all)), MatrixXd(B(rows, Eigen::all)), intercept, method,
                                 inner);
  };
  if (loss == RobustLoss::Tukey) {
    const TrimmedStart start = trimmed_start();
    X = start.X;
    c = start.c;
    scale = start.scale;
  } else {
    // Huber starts from the plain fit (auto's choice; spd-tls where that is spde, which has no rows):
    // from the Gram matrix's Cholesky factor when there is one (the start need not be more accurate
    // than the iterations' fits), else from the QR.
    std::optional<TriangularFactor> from_gram;
    if (base) {
      from_gram = downdated_gram_factor(A, B, valid.size() ? valid : VectorXd::Ones(m), *base, ea, eb);
    }
    const auto unweighted = [&] {
      if (!valid.size()) return TriangularFactor::from_data(A, B, intercept);
      TriangularFactor out(A.cols(), B.cols(), intercept);
      out.append(A, B, valid);
      return out;
    };
    const TriangularFactor plain_factor = from_gram ? std::move(*from_gram) : unweighted();
    FitOptions quiet = inner;
    quiet.diagnostics = false;
    FitResult plain = fit(reduce_for(plain_factor, quiet, method), method);
    if (method == Method::Auto && plain.diagnostics.chosen_method == Method::Spde) {
      plain = fit(reduce_for(plain_factor, quiet, Method::SpdTotalLeastSquares), Method::SpdTotalLeastSquares);
    }
    if (plain.ok()) {
      X = plain.X;
      c = intercept_offsets(plain_factor, X);
    } else {
      // The plain fit fails where a few rows decide it (a logger's 1e30 in B, which spd-tls's
      // start cannot survive): Huber then starts, as Tukey does, from least trimmed squares.
      const TrimmedStart start = trimmed_start();
      X = start.X;
      c = start.c;
    }
  }
  const int max_iterations = std::max(options.max_iterations, 1);
  Iterated fitted = iterate(A, B, method, inner, intercept, loss, k, X, c, scale, ea, eb, valid, max_iterations,
                            base ? &*base : nullptr);
  FitResult result = std::move(fitted.result);
  RobustReport report = robust_report(loss, k, fitted.weights, fitted.scale, fitted.iterations, fitted.converged);
  if (!fitted.converged && result.ok()) {
    result.warnings.emplace_back(Code::NotConverged,
                                 "the robust fit's weights had not settled after " +
                                     std::to_string(fitted.iterations) +
                                     " iterations (`max_iterations`): the last iterate is returned",
                                 "robust");
  }
  std::vector<Replicate> replicates;
  if (result.ok() && options.bootstrap > 0) {
    // Each replicate: the rows resampled (their counts multiply the weights), refitted robustly from
    // this estimate with its scale.
    FitOptions boot = inner;
    boot.bootstrap = options.bootstrap;
    const MatrixXd X_full = result.X;
    const VectorXd c_full = fitted.c;
    const double scale_full = fitted.scale;
    replicates = run_replicates(
        static_cast<std::size_t>(options.bootstrap), options, [&](std::size_t r) -> Replicate {
          VectorXd counts = resample_weights(m, options.seed, r);
          if (valid.size()) counts.array() *= valid.array();
          FitOptions rep = replicate_options(inner);
          try {
            Iterated again =
                iterate(A, B, method, rep, intercept, loss, k, X_full, c_full, scale_full, ea, eb, counts,
                        max_iterations);
            return replicate_of(std::move(again.result));
          } catch (const std::invalid_argument& e) {
            return Replicate{{}, e.what()};
          }
        });
    attach_bootstrap(result, replicates, boot, fitted.data);
  }
  result.robust = std::move(report);
  return RobustFit{std::move(result), std::move(fitted.factor), std::move(replicates)};
}

}  // namespace spdfit::detail
