#include "estimators/noise_weights.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "estimators/kernels.hpp"
#include "factor/reduce.hpp"
#include "noise/noise_checks.hpp"
#include "spdfit/format.hpp"
#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

std::optional<ScaledNoise> scaled_noise(const DynamicReduction& data) {
  const std::optional<NoiseModel>& model = data.options.noise;
  if (!model) return std::nullopt;
  ScaledNoise out;
  // A 2^-ea has the noise e 2^-ea, of covariance Sigma_A 2^-2ea (exact: powers of two).
  out.cov_a = times_power_of_two(model->cov_a(), -2 * data.exponent_a);
  out.cov_b = times_power_of_two(model->cov_b(), -2 * data.exponent_b);
  out.a_zero = model->a_is_zero();
  out.a_definite = model->a_is_positive_definite();
  out.b_definite = model->b_is_positive_definite();
  return out;
}

namespace {

// The columns whose rest rows are too few for the covariance `method` needs definite (B's for the
// methods that weight by Sigma_B, either for spd-tls and auto): N rows give rank N - 1 at most, so
// N <= columns makes it singular whatever the noise. Nothing when that is not why it refuses.
std::optional<std::uint64_t> too_few_for(const NoiseModel& model, Method method) {
  const auto rows = model.rest_rows();
  if (!rows || model.b_is_positive_definite()) return std::nullopt;
  const auto n = static_cast<std::uint64_t>(model.cov_a().rows());
  const auto d = static_cast<std::uint64_t>(model.cov_b().rows());
  switch (method) {
    case Method::SymmetricProcrustes:
    case Method::PsdLeastSquares:
      return *rows <= d ? std::optional<std::uint64_t>(d) : std::nullopt;
    case Method::TotalLeastSquares:
    case Method::TotalLeastSquaresSymmetric:
    case Method::TotalLeastSquaresPsd:
      if (model.a_is_zero()) return std::nullopt;
      return *rows <= d ? std::optional<std::uint64_t>(d) : std::nullopt;
    case Method::SpdTotalLeastSquares:
    case Method::Auto:
      if (model.a_is_positive_definite()) return std::nullopt;
      return *rows <= std::min(n, d) ? std::optional<std::uint64_t>(std::min(n, d)) : std::nullopt;
    default:
      return std::nullopt;
  }
}

}  // namespace

void throw_noise_refusal(const std::string& why, Method method, const std::optional<NoiseModel>& model) {
  if (model && too_few_for(*model, method)) throw InputError(why, Code::NoiseModel, bare(model->option_a()));
  throw OptionError(why, method == Method::Spde ? Code::OptionNotApplicable : Code::OptionValue, "noise");
}

std::optional<std::string> noise_refusal(const std::optional<NoiseModel>& model, Method method) {
  if (!model) return std::nullopt;
  const std::string name(to_string(method));
  const std::string a = model->option_a(), b = model->option_b();
  if (method != Method::Spde) {
    if (const std::optional<std::uint64_t> columns = too_few_for(*model, method)) {
      // Singular because the rest rows are too few, whatever the noise: say that, not "exact columns".
      const bool log = a == b;  // a log's rest_rows give both
      return std::to_string(*model->rest_rows()) + " rest rows for " + std::to_string(*columns) + " columns (" +
             (log ? a : a + ", " + b) +
             "): their sample covariances are singular whatever the noise (N rows give rank N - 1 at most), "
             "and " + name + " with a noise model needs " +
             (method == Method::SpdTotalLeastSquares || method == Method::Auto ? "one of them" : "B's") +
             " positive definite; " + (log ? "give more rest rows in " + a : std::string("record more rest rows")) +
             ": at least " + std::to_string(*columns + 1) +
             ", and hundreds for a good estimate (its relative error is about sqrt(2 / N))";
    }
  }
  switch (method) {
    case Method::LeastSquares:
      return std::nullopt;
    case Method::Spde:
      return "spde takes no noise model (it assumes equal noise in every column of A and B, in the units "
             "given): with one (" + a + ", " + b + "), use auto or spd-tls, the maximum-likelihood estimate";
    case Method::SymmetricProcrustes:
    case Method::PsdLeastSquares:
      if (model->b_is_positive_definite()) return std::nullopt;
      return name + " models noise in B only and weights each row's residual by the inverse of B's noise "
                    "covariance, but the covariance " + b + " gives is singular (B has exact columns or "
                    "directions): give B's noise, or use ls or spd-tls";
    case Method::TotalLeastSquares:
    case Method::TotalLeastSquaresSymmetric:
    case Method::TotalLeastSquaresPsd:
      if (model->a_is_zero() || model->b_is_positive_definite()) return std::nullopt;
      return name + " with a noise model is generalized total least squares, which needs B's noise covariance (" +
             b + ") positive definite unless A is exact (Sigma_A zero, from " + a +
             ": least squares): B has exact columns or directions here; use spd-tls";
    case Method::SpdTotalLeastSquares:
    case Method::Auto:
      if (model->a_is_positive_definite() || model->b_is_positive_definite()) return std::nullopt;
      return name + " with a noise model is the maximum-likelihood estimate, which needs X Sigma_A X + Sigma_B "
                    "positive definite for every positive definite X, so Sigma_A (" + a + ") or Sigma_B (" + b +
                    ") positive definite: both are singular (exact columns or directions in A and in B)";
  }
  return std::nullopt;
}

std::optional<double> noise_in_a_bias(const DynamicReduction& data, const ScaledNoise& noise) {
  const Index n = data.n, d = data.d;
  if (data.rank_a < n) return std::nullopt;
  SquareMatrix<Eigen::Dynamic> X;
  least_squares_kernel(data, X);
  if (data.square()) X = symmetric_part(X);
  const auto R = data.R11.triangularView<Eigen::Upper>();
  // b = m (A^T A)^-1 Sigma_A X = m R11^-1 R11^-T Sigma_A X; chi = ||R11 b L^-T||_F^2 with W = L L^T.
  const MatrixXd bias = static_cast<double>(data.dof_rows()) * R.solve(R.transpose().solve(MatrixXd(noise.cov_a * X)));
  const Eigen::LLT<MatrixXd> W(symmetric_part(MatrixXd(X.transpose() * noise.cov_a * X + noise.cov_b)));
  if (W.info() != Eigen::Success) return std::nullopt;
  const MatrixXd scaled = W.matrixL().solve(MatrixXd((data.R11 * bias).transpose())).transpose();
  const double chi = scaled.squaredNorm() / static_cast<double>(n * d);
  return std::isfinite(chi) ? std::optional<double>(chi) : std::nullopt;
}

std::optional<Warning> ignored_noise_warning(const DynamicReduction& data, Method method) {
  const std::optional<NoiseModel>& model = data.options.noise;
  // A quiet fit (diagnostics off: a bootstrap replicate, a Monte Carlo trial) has no warnings to
  // give, and the bias costs a least-squares solve.
  if (!model || model->a_is_zero() || !data.options.diagnostics) return std::nullopt;
  if (method != Method::LeastSquares && method != Method::SymmetricProcrustes && method != Method::PsdLeastSquares) {
    return std::nullopt;
  }
  const std::optional<ScaledNoise> noise = scaled_noise(data);
  const std::optional<double> bias = noise ? noise_in_a_bias(data, *noise) : std::nullopt;
  if (bias && *bias <= kNegligibleNoiseBias) return std::nullopt;  // auto's rule: negligible, said nowhere
  // One text for the three methods (hexapod identify states it once for all of them).
  std::string text = std::string(to_string(method)) + " models noise in B only: the noise in A that " +
                     model->option_a() + " gives is ignored, and biases the estimate towards zero";
  if (bias) text += " by about " + format_number(std::sqrt(*bias)) + " standard errors (root mean square over X's entries)";
  if (data.options.bootstrap > 0) text += "; the bootstrap's intervals, centred on the biased estimate, can miss the truth";
  text += data.square() ? "; spd-tls (or auto) models it" : "; tls models it";
  return Warning(Code::NoiseModelNotice, std::move(text), "noise_a");
}

Reduction without_noise(const Reduction& data) {
  auto copy = std::make_shared<DynamicReduction>(data_of(data));
  copy->options.noise.reset();
  return reduction_of(std::move(copy));
}

WhitenedB whiten_b(const DynamicReduction& data, const ScaledNoise& noise, double floor_s, bool vectors_a) {
  const Index n = data.n, d = data.d;
  WhitenedB out;
  out.floor_s = floor_s;
  // C = Sigma_B^1/2 and C^-1 from one eigendecomposition (Sigma_B > 0, checked by the caller).
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(noise.cov_b);
  const MatrixXd& V = eig.eigenvectors();
  const VectorXd root = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  out.C_s = symmetric_part(MatrixXd(V * root.asDiagonal() * V.transpose()));
  const MatrixXd C_inv = symmetric_part(MatrixXd(V * root.cwiseInverse().asDiagonal() * V.transpose()));

  // [A B] = Q R gives [A C, (B - floor A) C^-1] = Q [R11 C, (R12 - floor R11) C^-1; 0, R22 C^-1].
  MatrixXd top_b = data.R12;
  if (floor_s > 0.0) top_b -= floor_s * data.R11;
  MatrixXd Rw = MatrixXd::Zero(n + d, n + d);
  Rw.topLeftCorner(n, n).noalias() = data.R11 * out.C_s;
  Rw.topRightCorner(n, d).noalias() = top_b * C_inv;
  Rw.bottomRightCorner(d, d).noalias() = data.R22 * C_inv;
  // Each block scaled by a power of two to entries below 1, as TriangularFactor stores data.
  const int ka = scale_exponent(Rw.leftCols(n)).value_or(0);
  const int kb = scale_exponent(Rw.rightCols(d)).value_or(0);
  auto left = Rw.leftCols(n);
  auto right = Rw.rightCols(d);
  multiply_by_power_of_two(left, -ka);
  multiply_by_power_of_two(right, -kb);
  MatrixXd R;
  triangular_factor_into<MatrixXd>(Rw, R);

  out.data.options = data.options;
  out.data.options.noise.reset();
  // A_s C_s = A C 2^-(ea + eb) and (B_s - floor_s A_s) C_s^-1 = (B - floor A) C^-1: the whitened
  // data's exponents are ea + eb + ka and kb, and X_s = floor_s I + 2^(kb - ka) C_s Y_s C_s.
  reduce_into(R, data.m, n, data.exponent_a + data.exponent_b + ka, kb, out.data, vectors_a);
  out.shift = kb - ka;
  return out;
}

MatrixXd unwhiten_b(const WhitenedB& w, const MatrixXd& Y_s) {
  MatrixXd X = w.C_s * Y_s * w.C_s;
  multiply_by_power_of_two(X, w.shift);
  X = symmetric_part(X);
  X.diagonal().array() += w.floor_s;
  return X;
}

}  // namespace spdfit::detail
