#include "pipeline/offsets.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "factor/chunk_appender.hpp"
#include "numerics/cholesky_downdate.hpp"
#include "numerics/linalg.hpp"
#include "pipeline/units.hpp"
#include "spdfit/format.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// R's columns rescaled from a factor's exponents to (ea, eb): powers of two, exact.
MatrixXd in_exponents(const TriangularFactor& f, int ea, int eb) {
  MatrixXd R = f.R();
  auto left = R.leftCols(f.n());
  auto right = R.rightCols(f.d());
  multiply_by_power_of_two(left, f.exponent_a() - ea);
  multiply_by_power_of_two(right, f.exponent_b() - eb);
  return R;
}

// The factor of the centred data in the plain factor's scaled units, for a fit that has only the
// plain factor: a rank-one downdate of it, R^T R - m mu mu^T = Rc^T Rc (O((n + d)^2) rotations, no
// Gram matrix and no pass over the rows), where that loses at most half the digits of every
// column (offsets up to about 1e4 times the columns' spread), else straight from the rows,
// centred in two passes.
MatrixXd centred_factor(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                        const TriangularFactor& plain, const VectorXd& mean_scaled) {
  const MatrixXd R = plain.R();
  MatrixXd Rc;
  if (cholesky_downdate(R, std::sqrt(static_cast<double>(plain.rows())) * mean_scaled, Rc)) {
    bool accurate = true;
    for (Index j = 0; j < R.cols(); ++j) accurate = accurate && Rc.col(j).squaredNorm() > 1e-8 * R.col(j).squaredNorm();
    if (accurate) return Rc;
  }
  const TriangularFactor direct = TriangularFactor::from_data(A, B, true);
  return in_exponents(direct, plain.exponent_a(), plain.exponent_b());
}

// `centred`: the factor of [1 A B] when the caller has it (then no downdate), else null.
std::optional<Warning> intercept_warning(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                         const TriangularFactor& plain, const TriangularFactor* centred) {
  const Index n = plain.n(), d = plain.d(), m = plain.rows();
  const double dof = static_cast<double>(m - 1 - n);
  if (dof < 1.0 || A.rows() != m) return std::nullopt;
  const int ea = plain.exponent_a(), eb = plain.exponent_b();
  VectorXd mean(n + d);
  mean.head(n) = A.colwise().mean().transpose();
  mean.tail(d) = B.colwise().mean().transpose();
  VectorXd mean_scaled = mean;
  mean_scaled.head(n) = times_power_of_two(mean.head(n), -ea);
  mean_scaled.tail(d) = times_power_of_two(mean.tail(d), -eb);
  const MatrixXd Rc = centred ? in_exponents(*centred, ea, eb) : centred_factor(A, B, plain, mean_scaled);
  const MatrixXd Rc11 = Rc.topLeftCorner(n, n), R11 = plain.R11();
  const VectorXd diag = Rc11.diagonal().cwiseAbs(), plain_diag = R11.diagonal().cwiseAbs();
  const double tiny = 1e-12 * std::max(diag.maxCoeff(), std::numeric_limits<double>::min());
  if (diag.minCoeff() <= tiny || plain_diag.minCoeff() <= 1e-12 * plain_diag.maxCoeff()) return std::nullopt;
  // c = mu_B - Xc^T mu_A with Xc = Rc11^-1 Rc12, as Rc12^T w for w = Rc11^-T mu_A (which also
  // gives the intercept's leverage h = ||w||^2): O(n^2 + n d); X's solves only when c is far
  // from 0.
  const VectorXd w = Rc11.triangularView<Eigen::Upper>().transpose().solve(VectorXd(mean_scaled.head(n)));
  const MatrixXd Rc22 = Rc.bottomRightCorner(d, d);
  const VectorXd sigma = (Rc22.colwise().squaredNorm().transpose() / dof).cwiseSqrt();
  const VectorXd c = mean_scaled.tail(d) - Rc.topRightCorner(n, d).transpose() * w;
  const double h = w.squaredNorm();
  // Offsets of rounding's size are not offsets: noise-free data fit exactly either way.
  const VectorXd b_rms = (Rc22.colwise().squaredNorm().transpose() / static_cast<double>(m)).cwiseSqrt() +
                         mean_scaled.tail(d).cwiseAbs();
  double z_c = 0.0, z_x = 0.0;
  for (Index j = 0; j < d; ++j) {
    if (std::abs(c(j)) <= 1e-8 * (b_rms(j) + (Rc.col(n + j).norm() / std::sqrt(static_cast<double>(m))))) continue;
    const double se = sigma(j) * std::sqrt(1.0 / static_cast<double>(m) + h);
    z_c = std::max(z_c, se > 0.0 ? std::abs(c(j)) / se : std::numeric_limits<double>::infinity());
  }
  if (!(z_c > kOffsetStandardErrors)) return std::nullopt;
  MatrixXd Xc = Rc.topRightCorner(n, d), Xp = plain.R12();
  solve_upper_in_place(Rc11, Xc);
  solve_upper_in_place(R11, Xp);
  MatrixXd inverse = MatrixXd::Identity(n, n);  // Rc11^-1: (A_c^T A_c)^-1 = Rc11^-1 Rc11^-T
  solve_upper_in_place(Rc11, inverse);
  const VectorXd row_norms = inverse.rowwise().norm();
  const double x_scale = Xc.cwiseAbs().maxCoeff();
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < d; ++j) {
      const double shift = std::abs(Xp(i, j) - Xc(i, j));
      if (shift <= 1e-8 * x_scale) continue;
      const double se = sigma(j) * row_norms(i);
      z_x = std::max(z_x, se > 0.0 ? shift / se : std::numeric_limits<double>::infinity());
    }
  }
  if (!(z_x > kOffsetShift)) return std::nullopt;
  const VectorXd c_units = times_power_of_two(c, eb);
  const auto count = [](double z) {
    return std::isfinite(z) ? "about " + format_number(z, Precision::Brief) : std::string("infinitely many");
  };
  return Warning(Code::Bias,
                 "the data have constant offsets that a fit without them takes for signal: least squares with an "
                 "intercept (B ~= A X + 1 c^T) gives c = [" + format_numbers(c_units) + "], " + count(z_c) +
                     " standard errors from 0, and moves X by up to " + count(z_x) +
                     " of its standard errors: `offsets` estimate fits them with X (or `offsets` rest subtracts "
                     "the means of rows recorded at rest)",
                 "offsets");
}

}  // namespace

Tare rest_tare(const FitOptions& options, Index n, Index d) {
  if (!options.noise || !options.noise->rest_rows()) {
    throw OptionError("`offsets` rest subtracts the means of rows recorded at rest: give them (`rest_a` and `rest_b`, "
                      "or `rest_rows` of the same log), or use `offsets` estimate",
                      Code::OptionConflict, "offsets");
  }
  const NoiseModel& noise = *options.noise;
  if (noise.rest_mean_a().size() != n || noise.rest_mean_b().size() != d) {
    throw OptionError("`offsets` rest: the rest rows have " + std::to_string(noise.rest_mean_a().size()) + " and " +
                          std::to_string(noise.rest_mean_b().size()) + " columns but A and B have " +
                          std::to_string(n) + " and " + std::to_string(d),
                      Code::OptionConflict, "offsets");
  }
  return Tare{noise.rest_mean_a(), noise.rest_mean_b()};
}

TaredData tared_data(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                     const FitOptions& options) {
  Tare tare = rest_tare(options, A.cols(), B.cols());
  MatrixXd At = A.rowwise() - tare.a.transpose(), Bt = B.rowwise() - tare.b.transpose();
  return TaredData{std::move(tare), std::move(At), std::move(Bt)};
}

VectorXd intercept_offsets(const TriangularFactor& factor, const MatrixXd& X) {
  if (!factor.intercept() || factor.means().size() != factor.n() + factor.d() || X.rows() != factor.n() ||
      X.cols() != factor.d()) {
    return VectorXd();
  }
  return factor.means().tail(factor.d()) - X.transpose() * factor.means().head(factor.n());
}

TriangularFactor tared_factor(const TriangularFactor& centred, const Tare& tare) {
  const Index n = centred.n(), d = centred.d();
  if (!centred.intercept()) throw std::logic_error("tared_factor: the factor of [1 A B] is needed");
  if (centred.rows() == 0) return TriangularFactor(n, d);
  VectorXd shift = centred.means();
  shift.head(n) -= tare.a;
  shift.tail(d) -= tare.b;
  MatrixXd stacked(n + d + 1, n + d);
  stacked.topRows(n + d) = centred.R();
  const double root = std::sqrt(static_cast<double>(centred.rows()));
  stacked.row(n + d).head(n) = times_power_of_two(VectorXd(root * shift.head(n)), -centred.exponent_a()).transpose();
  stacked.row(n + d).tail(d) = times_power_of_two(VectorXd(root * shift.tail(d)), -centred.exponent_b()).transpose();
  return ChunkAppender::from_triangle(triangular_factor(stacked), n, centred.rows(), centred.exponent_a(),
                                      centred.exponent_b(), false, VectorXd(), 0.0);
}

FitOptions options_after_tare(const FitOptions& options) {
  FitOptions out = options;
  if (out.offsets == Offsets::Rest) out.offsets = Offsets::None;
  return out;
}

std::optional<FitOffsets> offsets_of(const FitResult& result, const TriangularFactor& factor, const FitOptions& options,
                                     const Tare* tare) {
  if (options.offsets == Offsets::Rest && tare) return tare->offsets();
  if (options.offsets != Offsets::Estimate || !result.ok()) return std::nullopt;
  VectorXd c = intercept_offsets(factor, result.X);
  if (c.size() == 0) return std::nullopt;
  return FitOffsets{Offsets::Estimate, std::move(c), {}, {}};
}

std::string untared_columns(const Eigen::Ref<const MatrixXd>& B, const VectorXd& rest_mean, const VectorXd& rest_variance,
                            std::uint64_t rest_rows) {
  if (rest_mean.size() != B.cols() || rest_variance.size() != B.cols() || rest_rows < 2 || B.rows() < 2) return {};
  const double m = static_cast<double>(B.rows());
  const Eigen::RowVectorXd mean = B.colwise().mean();
  const Eigen::RowVectorXd spread = ((B.rowwise() - mean).colwise().squaredNorm() / (m - 1.0)).cwiseSqrt();
  std::string columns;
  for (Index j = 0; j < B.cols(); ++j) {
    const double rest_se = std::sqrt(std::max(rest_variance(j), 0.0) / static_cast<double>(rest_rows));
    const double data_se = spread(j) / std::sqrt(m);
    const bool loaded = std::abs(rest_mean(j)) > kOffsetStandardErrors * rest_se;
    const bool same = std::abs(mean(j) - rest_mean(j)) <= kOffsetStandardErrors * std::hypot(rest_se, data_se);
    if (loaded && same) {
      columns += (columns.empty() ? "" : ", ") + std::string("B's column ") + std::to_string(j + 1) + ": " +
                 format_number(rest_mean(j)) + " at rest, " + format_number(mean(j)) + " in the data";
    }
  }
  return columns;
}

std::vector<Warning> offset_warnings(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                     const TriangularFactor* plain, const FitOptions& options, bool say_untared) {
  std::vector<Warning> out;
  if (options.offsets != Offsets::None || !options.diagnostics) return out;
  if (options.noise && options.noise->rest_rows()) {
    const NoiseModel noise = options.noise->resolved(A.cols(), B.cols());
    const std::string columns =
        untared_columns(B, noise.rest_mean_b(), noise.cov_b().diagonal(), *noise.rest_rows());
    if (!columns.empty()) {
      if (!say_untared) return out;
      out.push_back(Warning(Code::Bias,
                            "B looks untared: the rest rows' means are far from 0 and the data's column means are the "
                            "same (" + columns + "): a constant load is still in B, which the fit takes for signal; "
                            "`offsets` rest subtracts the rest rows' means",
                            "offsets"));
      return out;
    }
  }
  if (A.rows() <= A.cols() + 1) return out;
  std::optional<Warning> w;
  if (plain) {
    w = intercept_warning(A, B, *plain, nullptr);
  } else {
    // No factor at hand: one pass for the factor of [1 A B], and the plain one from it (no tare).
    const TriangularFactor centred = TriangularFactor::from_data(A, B, true);
    const Tare none{VectorXd::Zero(A.cols()), VectorXd::Zero(B.cols())};
    w = intercept_warning(A, B, tared_factor(centred, none), &centred);
  }
  if (w) out.push_back(std::move(*w));
  return out;
}

std::vector<Warning> offset_warnings_as_given(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                              const FitOptions& options) {
  if (options.offsets != Offsets::None || !options.diagnostics) return {};
  if (const std::optional<Units> units = units_of(options, A.cols(), B.cols())) {
    MatrixXd As = A, Bs = B;
    apply_units(*units, As, Bs);
    return offset_warnings(As, Bs, nullptr, options_in_units(options, *units));
  }
  return offset_warnings(A, B, nullptr, options);
}

}  // namespace spdfit::detail
