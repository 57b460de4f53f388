#include "pipeline/row_scores.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "numerics/linalg.hpp"
#include "pipeline/sentinels.hpp"
#include "spdfit/format.hpp"
#include "spdfit/method.hpp"
#include "spdfit/noise_model.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// The consistency constant of the MAD at the normal distribution: 1 / Phi^-1(3/4).
constexpr double kRowScoreMadToSigma = 1.482602218505602;
// Rows named in the warning; the count says how many more.
constexpr std::size_t kNamedDominantRows = 5;
// A row that alone decides a direction (h_i = 1) has no residual left to judge it by: its score is
// its residual over this floor's root.
constexpr double kRowScoreLeverageFloor = 1e-12;
// Rows beyond A's columns needed for the median and the MAD of the rows' scores to judge a row by.
constexpr Eigen::Index kRowScoreMinExtraRows = 10;
// A row whose residual is this small against the row itself is fitted to rounding, whatever its z.
constexpr double kRowScoreRounding = 1e-8;
// The leverages come from R11^-1 where A's smallest singular value is this many times the rank
// cut-off or more (the SVD's rank is then A's column count whatever its rounding).
constexpr double kRowScoreFullRankMargin = 4.0;
// Above this many multiply-adds the check is made only when the diagnostics are read.
constexpr double kRowScoreUnreadFlops = 1e8;

}  // namespace

namespace {

// The median of `values` (not empty), which it reorders.
double median_in_place(std::vector<double>& values) {
  const std::size_t k = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  const double upper = values[k];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k)));
}

}  // namespace

double median(std::vector<double> values) { return median_in_place(values); }

double robust_spread(std::vector<double>& values, double* center) {
  const double mid = median_in_place(values);
  if (center) *center = mid;
  for (double& v : values) v = std::abs(v - mid);
  return kRowScoreMadToSigma * median_in_place(values);
}

MatrixXd residual_covariance(const MatrixXd& X, Method method, const FitOptions& options) {
  const Index n = X.rows(), d = X.cols();
  if (options.noise) {
    const NoiseModel model = options.noise->resolved(n, d);
    return X.transpose() * model.cov_a() * X + model.cov_b();
  }
  if (models_noise_in_a(method)) {
    MatrixXd S = X.transpose() * X;
    S.diagonal().array() += options.noise_ratio * options.noise_ratio;
    return S;
  }
  return MatrixXd::Identity(d, d);
}

VectorXd whitened_residuals(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const MatrixXd& X,
                            const VectorXd& c, const MatrixXd& covariance) {
  VectorXd out;
  whitened_residuals_into(A, B, X, c, covariance, out);
  return out;
}

void whitened_residuals_into(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const MatrixXd& X,
                             const VectorXd& c, const MatrixXd& covariance, VectorXd& out) {
  // The methods without noise in A and without a noise model: residuals as they are (no
  // factorization: at d = 1000 the Cholesky factor and its inverse cost 3.5% of a procrustes fit).
  const bool identity = covariance.isIdentity(0.0);
  const Index m = A.rows(), n = A.cols(), d = B.cols();
  MatrixXd Linv_t;
  if (!identity) {
    MatrixXd S = 0.5 * (covariance + covariance.transpose());
    const double top = S.size() ? S.diagonal().cwiseAbs().maxCoeff() : 0.0;
    Eigen::LLT<MatrixXd> llt(S);
    if (llt.info() != Eigen::Success || !(top > 0.0)) {
      S.diagonal().array() += std::max(top, 1.0) * 1e-12;
      llt.compute(S);
    }
    Linv_t = MatrixXd(llt.matrixL().solve(MatrixXd::Identity(d, d))).transpose();
  }
  // A block of rows at a time (no matrix of m rows: its fresh pages would cost more than the
  // arithmetic at these widths): residuals, then whitened by L^-1. For the narrow matrices of a fit
  // (n, d up to 16) a blocked GEMM's packing costs more than its arithmetic: see below.
  constexpr Index kBlockRows = 2048, kNarrow = 16;
  out.resize(m);
  MatrixXd residual, whitened;
  VectorXd squares;
  for (Index i0 = 0; i0 < m; i0 += kBlockRows) {
    const Index r = std::min(kBlockRows, m - i0);
    if (n <= kNarrow && d <= kNarrow) {
      // Column by column (rank-one updates along the block's rows, which vectorize), and the
      // squared norms summed over columns: no pass reads a row across columns.
      residual = -B.middleRows(i0, r);
      if (c.size() == d) residual.rowwise() += c.transpose();
      for (Index k = 0; k < n; ++k) residual.noalias() += A.col(k).segment(i0, r) * X.row(k);
      squares.setZero(r);
      if (identity) {  // the products below with L^-T = I, to the bit
        for (Index j = 0; j < d; ++j) squares += residual.col(j).cwiseAbs2();
        out.segment(i0, r) = squares.cwiseSqrt();
        continue;
      }
      for (Index j = 0; j < d; ++j) {
        // Column j of residual L^-T: L^-T is upper triangular, so rows k <= j of Linv_t.
        whitened.noalias() = residual.leftCols(j + 1) * Linv_t.col(j).head(j + 1);
        squares += whitened.col(0).cwiseAbs2();
      }
      out.segment(i0, r) = squares.cwiseSqrt();
      continue;
    }
    multiply(A.middleRows(i0, r), false, X, false, residual);
    residual -= B.middleRows(i0, r);
    if (c.size() == d) residual.rowwise() += c.transpose();
    if (identity) {
      out.segment(i0, r) = residual.rowwise().norm();
      continue;
    }
    multiply(residual, false, Linv_t, false, whitened);
    out.segment(i0, r) = whitened.rowwise().norm();
  }
}

VectorXd robust_z_scores(const VectorXd& x) {
  const Index m = x.size();
  if (m < 3) return VectorXd::Zero(m);
  // One work array for both medians: at m = 1e5 each array of m fresh values costs more than its
  // median.
  std::vector<double> work(x.data(), x.data() + m);
  double mid = 0.0;
  const double spread = robust_spread(work, &mid);
  if (!(spread > 0.0)) return VectorXd::Zero(m);
  return (x.array() - mid) / spread;
}

VectorXd row_scores(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const FitResult& result,
                    const TriangularFactor& factor, const FitOptions& options) {
  const Index m = A.rows(), n = A.cols(), d = B.cols();
  if (!result.ok() || result.X.rows() != n || result.X.cols() != d || !result.X.allFinite() || m <= n + 1 ||
      factor.rows() != m) {
    return VectorXd();
  }
  const MatrixXd& X = result.X;
  const Method method = result.diagnostics.chosen_method.value_or(result.method);
  // Whitened residuals (the offsets c with an intercept).
  const bool intercept = factor.intercept();
  const VectorXd c = intercept && result.offsets && result.offsets->c.size() == d ? result.offsets->c : VectorXd();
  VectorXd score = whitened_residuals(A, B, X, c, residual_covariance(X, method, options));
  // Leverages h_i = ||a_i V_r S_r^-1||^2 from the SVD of R11 in the data's units (A^T A = R11^T
  // R11; the centred A's with an intercept, plus 1/m), directions below the rank cut-off left out.
  // Where the fit's singular values of A (the same R11's) put every one well above the cut-off,
  // V S^-1 spans what R11^-1 does and h_i = ||a_i R11^-1||^2: a triangular inverse instead of
  // an SVD with vectors.
  const MatrixXd R11 = times_power_of_two(MatrixXd(factor.R11()), factor.exponent_a());
  const bool centre = intercept && factor.means().size() == n + d;
  const VectorXd& s = result.diagnostics.singular_values_a;
  const double cutoff_ratio = options.rank_cutoff(m, n);
  MatrixXd map;
  // Full rank: each block's a_i R11^-1 by a triangular solve from the right (half a product's
  // multiply-adds, no inverse formed); else the SVD's V_r S_r^-1.
  const bool triangular = n > 0 && s.size() == n && s(n - 1) > kRowScoreFullRankMargin * cutoff_ratio * s(0);
  if (!triangular) {
    const Svd dec = svd(R11, false, true);
    const double largest = dec.s.size() ? dec.s(0) : 0.0;
    const double cutoff = cutoff_ratio * largest;
    Index rank = 0;
    while (rank < dec.s.size() && dec.s(rank) > cutoff && dec.s(rank) > 0.0) ++rank;
    map = dec.V.leftCols(rank) * dec.s.head(rank).cwiseInverse().asDiagonal();
  }
  // A block of rows at a time, into the whitened residuals' vector: no matrix or vector of m rows
  // beside it (at m = 1e5 and n = 3 their fresh pages cost a plain fit 15 % of its time).
  constexpr Index kBlockRows = 2048;
  MatrixXd centred, projected;
  for (Index i0 = 0; i0 < m; i0 += kBlockRows) {
    const Index r = std::min(kBlockRows, m - i0);
    if (triangular) {
      projected = A.middleRows(i0, r);
      if (centre) projected.rowwise() -= factor.means().head(n).transpose();
      solve_upper_from_right_in_place(R11, projected);
    } else if (centre) {
      centred = A.middleRows(i0, r).rowwise() - factor.means().head(n).transpose();
      multiply(centred, false, map, false, projected);
    } else {
      multiply(A.middleRows(i0, r), false, map, false, projected);
    }
    auto h = projected.rowwise().squaredNorm().array();
    auto block = score.segment(i0, r).array();
    if (intercept) {
      block /= ((1.0 - (h + 1.0 / static_cast<double>(m))).max(kRowScoreLeverageFloor)).sqrt();
    } else {
      block /= (1.0 - h).max(kRowScoreLeverageFloor).sqrt();
    }
  }
  return score;
}

std::optional<Warning> dominant_rows_warning(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                             const FitResult& result, const TriangularFactor& factor,
                                             const FitOptions& options, const RowNumbers& numbers) {
  if (!options.diagnostics) return std::nullopt;
  const double flops = static_cast<double>(A.rows()) * static_cast<double>(A.cols()) *
                       static_cast<double>(A.cols() + B.cols());
  if (!options.reported_diagnostics && flops > kRowScoreUnreadFlops) return std::nullopt;
  if (A.rows() - A.cols() < kRowScoreMinExtraRows) return std::nullopt;
  const VectorXd score = row_scores(A, B, result, factor, options);
  if (score.size() == 0 || !score.allFinite()) return std::nullopt;
  const VectorXd z = robust_z_scores(score);
  std::vector<Index> flagged;
  for (Index i = 0; i < z.size(); ++i) {
    if (!(z(i) > kDominantZScore)) continue;
    // Noise-free data: residuals of rounding's size, whose spread says nothing.
    Eigen::RowVectorXd residual = A.row(i) * result.X - B.row(i);
    double row_size = A.row(i).norm() * result.X.norm() + B.row(i).norm();
    if (result.offsets && result.offsets->c.size() == B.cols()) {
      residual += result.offsets->c.transpose();
      row_size += result.offsets->c.norm();
    }
    if (residual.norm() <= kRowScoreRounding * row_size) continue;
    // A row holding a logger's code is named by the sentinel warning.
    const bool sentinel = (A.row(i).cwiseAbs().array() >= kSentinelMagnitude).any() ||
                          (B.row(i).cwiseAbs().array() >= kSentinelMagnitude).any();
    if (!sentinel) flagged.push_back(i);
  }
  if (flagged.empty()) return std::nullopt;
  std::vector<Index> by_score = flagged;
  std::stable_sort(by_score.begin(), by_score.end(), [&](Index x, Index y) { return z(x) > z(y); });
  std::string named;
  for (std::size_t k = 0; k < by_score.size() && k < kNamedDominantRows; ++k) {
    const Index i = by_score[k];
    named += (k == 0 ? "" : ", ") + std::to_string(file_row(numbers, i)) + " (z = " + format_number(z(i)) + ")";
  }
  const bool one = flagged.size() == 1;
  std::string text = (one ? "row " : "rows ") + named;
  if (flagged.size() > kNamedDominantRows) text += " and " + std::to_string(flagged.size() - kNamedDominantRows) + " more";
  text += std::string(one ? " dominates" : " dominate") + " the fit: the robust z-score (median and MAD of all " +
          std::to_string(A.rows()) + " rows') of " + (one ? "its" : "their") +
          " residual, whitened by the noise model and studentized by " + (one ? "its" : "their") +
          " leverage in A, is above " + format_number(kDominantZScore) +
          ", which clean data do not reach: gross errors in B, or wrong values in A? Check " +
          (one ? "it" : "them") + ", and leave " + (one ? "it" : "them") + " out of the fit if " +
          (one ? "it is" : "they are") + " (`rows` chooses the rows fitted)";
  return Warning(Code::Outliers, text, "rows");
}

}  // namespace spdfit::detail
