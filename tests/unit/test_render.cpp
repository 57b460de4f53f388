// The library's rendering (spdfit/render.hpp, spdfit/format.hpp): JSON that reads back bit for
// bit in the Exact style (every double, +-inf and NaN), the Contract style's nulls, errors that
// name the field, and the number formatter against C's printf.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "spdfit/compare.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/nearest_correlation.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/render.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using test::Generator;

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- bitwise comparison (NaN equal to NaN; -0 not equal to +0) ---------------------------------

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || bits(a) == bits(b); }

::testing::AssertionResult same_matrix(const MatrixXd& a, const MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure() << "shape " << a.rows() << "x" << a.cols() << " vs " << b.rows() << "x"
                                         << b.cols();
  }
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (!same(a.data()[i], b.data()[i])) {
      return ::testing::AssertionFailure() << "entry " << i << ": " << a.data()[i] << " vs " << b.data()[i];
    }
  }
  return ::testing::AssertionSuccess();
}

void expect_same(const std::optional<double>& a, const std::optional<double>& b, const char* what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_TRUE(same(*a, *b)) << what << ": " << *a << " vs " << *b;
  }
}

void expect_same(const SpectrumUncertainty& a, const SpectrumUncertainty& b) {
  EXPECT_TRUE(same_matrix(a.estimate, b.estimate));
  EXPECT_TRUE(same_matrix(a.standard_errors, b.standard_errors));
  EXPECT_TRUE(same_matrix(a.lower, b.lower));
  EXPECT_TRUE(same_matrix(a.upper, b.upper));
  EXPECT_EQ(a.clusters, b.clusters);
  EXPECT_EQ(a.failed, b.failed);
}

void expect_same(const Diagnostics& a, const Diagnostics& b) {
  EXPECT_EQ(a.m, b.m);
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.d, b.d);
  EXPECT_EQ(a.rank_a, b.rank_a);
  EXPECT_EQ(a.rank_b, b.rank_b);
  for (auto [x, y] : {std::pair{a.cond_a, b.cond_a}, {a.cond_b, b.cond_b}, {a.cond_a_scaled, b.cond_a_scaled},
                      {a.cond_b_scaled, b.cond_b_scaled}, {a.residual_norm, b.residual_norm}}) {
    EXPECT_TRUE(same(x, y)) << x << " vs " << y;
  }
  EXPECT_TRUE(same_matrix(a.singular_values_a, b.singular_values_a));
  EXPECT_TRUE(same_matrix(a.singular_values_b, b.singular_values_b));
  EXPECT_EQ(a.symmetric, b.symmetric);
  EXPECT_EQ(a.positive_definite, b.positive_definite);
  EXPECT_EQ(a.positive_semidefinite, b.positive_semidefinite);
  expect_same(a.min_eigenvalue, b.min_eigenvalue, "min_eigenvalue");
  expect_same(a.max_eigenvalue, b.max_eigenvalue, "max_eigenvalue");
  expect_same(a.area_criterion, b.area_criterion, "area_criterion");
  expect_same(a.area_criterion_minimum, b.area_criterion_minimum, "area_criterion_minimum");
  EXPECT_EQ(a.cross_term_positive_definite, b.cross_term_positive_definite);
  expect_same(a.tls_sigma_n, b.tls_sigma_n, "tls_sigma_n");
  expect_same(a.tls_sigma_n1, b.tls_sigma_n1, "tls_sigma_n1");
  expect_same(a.tls_correction_norm, b.tls_correction_norm, "tls_correction_norm");
  expect_same(a.tls_v22_min_singular_value, b.tls_v22_min_singular_value, "tls_v22_min_singular_value");
  expect_same(a.noise_sigma, b.noise_sigma, "noise_sigma");
  EXPECT_EQ(a.iterations, b.iterations);
  expect_same(a.gradient_norm, b.gradient_norm, "gradient_norm");
  EXPECT_EQ(a.converged, b.converged);
  ASSERT_EQ(a.certificate.has_value(), b.certificate.has_value());
  if (a.certificate) {
    EXPECT_TRUE(same(a.certificate->primal_min_eig, b.certificate->primal_min_eig));
    EXPECT_TRUE(same(a.certificate->dual_min_eig, b.certificate->dual_min_eig));
    EXPECT_TRUE(same(a.certificate->complementarity, b.certificate->complementarity));
    EXPECT_TRUE(same(a.certificate->duality_gap, b.certificate->duality_gap));
  }
  EXPECT_EQ(a.chosen_method, b.chosen_method);
  ASSERT_EQ(a.reason.has_value(), b.reason.has_value());
  if (a.reason) {
    EXPECT_EQ(std::tie(a.reason->code, a.reason->text), std::tie(b.reason->code, b.reason->text));
  }
}

void expect_same(const FitResult& a, const FitResult& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_TRUE(same_matrix(a.X, b.X));
  expect_same(a.diagnostics, b.diagnostics);
  // JSON keeps each warning's code and text, not the option it names (Warning::subject).
  ASSERT_EQ(a.warnings.size(), b.warnings.size());
  for (std::size_t k = 0; k < a.warnings.size(); ++k) {
    EXPECT_EQ(std::tie(a.warnings[k].code, a.warnings[k].text), std::tie(b.warnings[k].code, b.warnings[k].text));
  }
  EXPECT_EQ(a.row_names, b.row_names);
  EXPECT_EQ(a.column_names, b.column_names);
  ASSERT_EQ(a.bootstrap.has_value(), b.bootstrap.has_value());
  if (!a.bootstrap) return;
  const Bootstrap &x = *a.bootstrap, &y = *b.bootstrap;
  EXPECT_EQ(std::tie(x.replicates, x.failed, x.seed, x.method, x.scheme, x.group_rows, x.groups),
            std::tie(y.replicates, y.failed, y.seed, y.method, y.scheme, y.group_rows, y.groups));
  EXPECT_TRUE(same_matrix(x.standard_errors, y.standard_errors));
  EXPECT_TRUE(same_matrix(x.bias, y.bias));
  EXPECT_TRUE(same(x.interval.level, y.interval.level));
  EXPECT_TRUE(same_matrix(x.interval.lower, y.interval.lower));
  EXPECT_TRUE(same_matrix(x.interval.upper, y.interval.upper));
  ASSERT_EQ(x.eigenvalues.has_value(), y.eigenvalues.has_value());
  if (x.eigenvalues) expect_same(*x.eigenvalues, *y.eigenvalues);
}

// A noisy 6 x 6 problem of m rows (the thesis' hexapod).
std::pair<MatrixXd, MatrixXd> hexapod_data(Eigen::Index m, std::uint64_t seed) {
  hexapod::SimulationOptions options;
  options.samples = m;
  options.noise_var = 0.86;
  const hexapod::Measurements data = hexapod::simulate(hexapod::thesis_mass_matrix(), options, seed);
  return {data.A, data.B};
}

// ---- the formatter ---------------------------------------------------------------------------

std::string printf_text(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

TEST(Format, NumbersAreCsPrintfInTheNamedPrecision) {
  Generator g(3);
  std::vector<double> values = {0.0, -0.0, 1.0, 0.1, 123456.0, 1e-300, -2.5e300, kInf, -kInf, 0.0001234567};
  for (int k = 0; k < 200; ++k) values.push_back(std::ldexp(g.normal(), static_cast<int>(g.uniform(-60, 60))));
  for (double v : values) {
    if (v == 0.0) continue;  // -0 is shown as 0 (below), where printf writes "-0"
    EXPECT_EQ(format_number(v), printf_text("%.3g", v));
    EXPECT_EQ(format_number(v, Precision::Brief), printf_text("%.3g", v));
    EXPECT_EQ(format_number(v, Precision::Medium), printf_text("%.4g", v));
    EXPECT_EQ(format_number(v, Precision::Full), printf_text("%.6g", v));
    EXPECT_EQ(format_percent(v, Precision::Medium), printf_text("%.4g", 100.0 * v) + "%");
  }
  EXPECT_EQ(format_percent(0.95, Precision::Medium), "95%");
  // A value that rounds to zero is shown without a sign it does not show.
  EXPECT_EQ(format_number(-0.0), "0");
  EXPECT_EQ(format_number(-1e-20, Precision::Brief), "-1e-20");
  EXPECT_EQ(format_fixed(-0.00001, 2), "0.00");
  EXPECT_EQ(format_fixed(-0.5, 2), "-0.50");
  EXPECT_EQ(format_percent(0.025), "2.5%");
}

TEST(Format, FixedSwitchesToScientificFrom1e5AndShowsNaNAsADash) {
  EXPECT_EQ(format_fixed(3.14159), "3.1416");
  EXPECT_EQ(format_fixed(99999.4, 2), "99999.40");
  EXPECT_EQ(format_fixed(100000.0, 2), "1.00e+05");
  EXPECT_EQ(format_fixed(-123456.0, 1), "-1.2e+05");
  EXPECT_EQ(format_fixed(kNaN), "-");
  EXPECT_EQ(format_fixed(kInf, 3), "inf");
  EXPECT_EQ(format_fixed(-kInf, 3), "-inf");
}

TEST(Format, SideBySideWrapsBlocksAndTrimsLineEnds) {
  const MatrixXd A = (MatrixXd(2, 2) << 1.0, -2.0, 3.0, 4.5).finished();
  const std::string text = format_side_by_side({"first", "second"}, {A, 1e6 * A}, 2);
  EXPECT_EQ(text,
            "first          second\n"
            "  1.00 -2.00     1.00e+06 -2.00e+06\n"
            "  3.00  4.50     3.00e+06  4.50e+06\n\n");
  // A width that holds one block a line puts each on its own lines.
  const std::string narrow = format_side_by_side({"first", "second"}, {A, A}, 2, 20);
  EXPECT_EQ(narrow, "first\n  1.00 -2.00\n  3.00  4.50\n\nsecond\n  1.00 -2.00\n  3.00  4.50\n\n");
}

// ---- JSON: Exact reads back bit for bit ------------------------------------------------------

TEST(RenderJson, EveryDoubleReadsBackBitForBit) {
  // The shortest text that reads back: random bit patterns over the whole range, subnormals, the
  // extremes, both zeros and the non-finite values, as X of a hand-made result.
  std::mt19937_64 engine(11);
  MatrixXd X(40, 25);
  for (Eigen::Index i = 0; i < X.size(); ++i) {
    std::uint64_t b = engine();
    double x;
    std::memcpy(&x, &b, sizeof x);
    X.data()[i] = std::isnan(x) ? 1.0 : x;
  }
  const double specials[] = {0.0, -0.0, std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                             kInf, -kInf, kNaN, 0.1, 1.0 / 3.0};
  for (std::size_t k = 0; k < std::size(specials); ++k) X(0, static_cast<Eigen::Index>(k)) = specials[k];
  FitResult r;
  r.method = Method::SymmetricProcrustes;
  r.status = Status::Success;
  r.X = X;
  r.diagnostics.m = 40;
  r.diagnostics.n = 40;
  r.diagnostics.d = 25;
  r.diagnostics.cond_a = kInf;  // a singular A
  r.diagnostics.noise_sigma = kNaN;
  r.diagnostics.min_eigenvalue = -kInf;
  const FitResult back = from_json<FitResult>(to_json(r, JsonStyle::Exact));
  EXPECT_TRUE(same_matrix(back.X, X));
  expect_same(back, r);
  EXPECT_EQ(to_json(back, JsonStyle::Exact), to_json(r, JsonStyle::Exact));
}

TEST(RenderJson, EveryMethodsResultRoundTrips) {
  const auto [A, B] = hexapod_data(30, 5);
  FitOptions options;
  options.noise_ratio = 0.8;
  for (const FitResult& r : fit_all(A, B, options)) {
    SCOPED_TRACE(std::string(to_string(r.method)));
    expect_same(from_json<FitResult>(to_json(r, JsonStyle::Exact)), r);
  }
  const FitResult automatic = fit(A, B, Method::Auto, options);
  ASSERT_TRUE(automatic.diagnostics.reason.has_value());
  expect_same(from_json<FitResult>(to_json(automatic, JsonStyle::Exact)), automatic);
}

TEST(RenderJson, BootstrapsRoundTripInBothSchemes) {
  const auto [A, B] = hexapod_data(40, 6);
  FitOptions options;
  options.bootstrap = 25;
  options.threads = 1;
  const FitResult r = fit(A, B, Method::Spde, options);
  ASSERT_TRUE(r.bootstrap && r.bootstrap->eigenvalues);
  expect_same(from_json<FitResult>(to_json(r, JsonStyle::Exact)), r);
  // The parts on their own.
  const Bootstrap b = from_json<Bootstrap>(to_json(*r.bootstrap, JsonStyle::Exact));
  FitResult holder = r;
  holder.bootstrap = b;
  expect_same(holder, r);
  expect_same(from_json<SpectrumUncertainty>(to_json(*r.bootstrap->eigenvalues, JsonStyle::Exact)),
              *r.bootstrap->eigenvalues);
  // A streaming bootstrap's groups (set by hand: the scheme is a field like the others).
  FitResult streamed = r;
  streamed.bootstrap->scheme = "poisson_groups";
  streamed.bootstrap->group_rows = 4096;
  streamed.bootstrap->groups = 3;
  expect_same(from_json<FitResult>(to_json(streamed, JsonStyle::Exact)), streamed);
  expect_same(from_json<FitResult>(to_json(streamed, JsonStyle::Contract)), streamed);
}

void expect_same(const NoiseModel& a, const NoiseModel& b) {
  EXPECT_EQ(a.source(), b.source());
  EXPECT_TRUE(same_matrix(a.cov_a(), b.cov_a()));
  EXPECT_TRUE(same_matrix(a.cov_b(), b.cov_b()));
  EXPECT_TRUE(same_matrix(a.std_a(), b.std_a()));
  EXPECT_TRUE(same_matrix(a.std_b(), b.std_b()));
  EXPECT_EQ(a.rest_rows(), b.rest_rows());
  EXPECT_TRUE(same_matrix(a.rest_mean_a(), b.rest_mean_a()));
  EXPECT_TRUE(same_matrix(a.rest_mean_b(), b.rest_mean_b()));
  EXPECT_EQ(a.rest_a_path(), b.rest_a_path());
  EXPECT_EQ(a.warnings(), b.warnings());
  EXPECT_EQ(std::make_tuple(a.a_is_zero(), a.a_is_positive_definite(), a.b_is_positive_definite()),
            std::make_tuple(b.a_is_zero(), b.a_is_positive_definite(), b.b_is_positive_definite()));
}

TEST(RenderJson, TheNoiseModelOfAFitRoundTrips) {
  const auto [A, B] = hexapod_data(60, 15);
  Generator g(16);
  const std::vector<NoiseModel> models = {
      NoiseModel::from_std(0.3, 0.7),
      NoiseModel::from_cov(test::Generator(17).spd(6), test::Generator(18).spd(6)),
      NoiseModel::from_rest(0.2 * g.gaussian(40, 6), 0.5 * g.gaussian(40, 6) + MatrixXd::Constant(40, 6, 3.0)),
  };
  for (const NoiseModel& model : models) {
    SCOPED_TRACE(std::string(to_string(model.source())));
    FitOptions options;
    options.noise = model;
    const FitResult r = fit(A, B, Method::SpdTotalLeastSquares, options);
    ASSERT_TRUE(r.ok() && r.diagnostics.noise_model.has_value()) << r.message;
    const FitResult back = from_json<FitResult>(to_json(r, JsonStyle::Exact));
    expect_same(back, r);
    ASSERT_TRUE(back.diagnostics.noise_model.has_value());
    expect_same(*back.diagnostics.noise_model, *r.diagnostics.noise_model);
  }
}

TEST(RenderJson, PartsRoundTripOnTheirOwn) {
  const auto [A, B] = hexapod_data(30, 7);
  FitOptions options;
  options.min_eig = 0.01;
  const FitResult r = fit(A, B, Method::PsdLeastSquares, options);
  ASSERT_TRUE(r.diagnostics.certificate.has_value());
  expect_same(from_json<Diagnostics>(to_json(r.diagnostics, JsonStyle::Exact)), r.diagnostics);
  const PsdCertificate c = from_json<PsdCertificate>(to_json(*r.diagnostics.certificate, JsonStyle::Exact));
  EXPECT_TRUE(same(c.duality_gap, r.diagnostics.certificate->duality_gap));
  EXPECT_TRUE(same(c.primal_min_eig, r.diagnostics.certificate->primal_min_eig));
  const AutoReason reason = from_json<AutoReason>(to_json(AutoReason{"few_samples", "m < 5 n \"quoted\"\n"}));
  EXPECT_EQ(reason.code, "few_samples");
  EXPECT_EQ(reason.text, "m < 5 n \"quoted\"\n");
  Interval interval;
  interval.level = 0.9;
  interval.lower = MatrixXd::Constant(2, 3, -kInf);
  interval.upper = MatrixXd::Constant(2, 3, 1.5);
  const Interval back = from_json<Interval>(to_json(interval, JsonStyle::Exact));
  EXPECT_TRUE(same_matrix(back.lower, interval.lower));
  EXPECT_TRUE(same_matrix(back.upper, interval.upper));
}

TEST(RenderJson, AFailedResultKeepsItsMessageAndNames) {
  MatrixXd A(3, 2);
  A << 1, 0, 2, 0, 3, 0;  // rank 1, a zero singular value: spde fails, cond(A) = inf
  FitResult r = fit(A, A, Method::Spde);
  ASSERT_FALSE(r.ok());
  r.row_names = {"a", "b"};
  r.column_names = {"c", "\xc3\xa9"};
  const FitResult back = from_json<FitResult>(to_json(r, JsonStyle::Exact));
  expect_same(back, r);
  EXPECT_FALSE(back.message.empty());
  EXPECT_TRUE(std::isinf(back.diagnostics.cond_a));
}

TEST(RenderJson, ContractWritesNullForNonFiniteAndReadsItAsNaN) {
  MatrixXd A(3, 2);
  A << 1, 0, 2, 0, 3, 0;  // cond(A) = inf
  const FitResult r = fit(A, A, Method::LeastSquares);
  ASSERT_TRUE(std::isinf(r.diagnostics.cond_a));
  const std::string contract = to_json(r);
  EXPECT_NE(contract.find("\"cond_a\": null"), std::string::npos) << contract;
  EXPECT_EQ(contract.back(), '\n');
  EXPECT_NE(to_json(r, JsonStyle::Exact).find("\"cond_a\":\"inf\""), std::string::npos);
  EXPECT_TRUE(std::isnan(from_json<FitResult>(contract).diagnostics.cond_a));
}

TEST(RenderJson, NearestResultsRoundTrip) {
  Generator g(4);
  MatrixXd C = g.gaussian(5, 5);
  C = (C + C.transpose()).eval();
  const NearestResult clip = nearest_spd(C, EigenvalueFloor::relative_to_largest(1e-3));
  const NearestResult back = from_json<NearestResult>(to_json(clip, JsonStyle::Exact));
  EXPECT_TRUE(same_matrix(back.X, clip.X));
  EXPECT_TRUE(same(back.distance, clip.distance) && same(back.min_eig, clip.min_eig));
  EXPECT_TRUE(same(back.min_eigenvalue_before, clip.min_eigenvalue_before));
  EXPECT_EQ(std::tie(back.clipped, back.iterations, back.converged, back.cholesky_ok, back.warnings),
            std::tie(clip.clipped, clip.iterations, clip.converged, clip.cholesky_ok, clip.warnings));
  const MatrixXd D = C.diagonal().cwiseAbs().array().sqrt().inverse().matrix().asDiagonal();
  MatrixXd R = D * C * D;
  R.diagonal().setOnes();
  const NearestResult newton = nearest_correlation(R);
  const NearestResult nb = from_json<NearestResult>(to_json(newton, JsonStyle::Exact));
  EXPECT_TRUE(same_matrix(nb.X, newton.X));
  EXPECT_TRUE(same(nb.gradient_norm, newton.gradient_norm));
  EXPECT_EQ(nb.iterations, newton.iterations);
}

void expect_same(const LinearSystemResult& a, const LinearSystemResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(std::tie(a.m, a.n, a.p, a.shape, a.rank, a.nullity, a.refinement_steps, a.consistent,
                     a.finite_solution_dimension, a.at_infinity_dimension),
            std::tie(b.m, b.n, b.p, b.shape, b.rank, b.nullity, b.refinement_steps, b.consistent,
                     b.finite_solution_dimension, b.at_infinity_dimension));
  for (auto [x, y] : {std::pair{a.rank_tolerance, b.rank_tolerance}, {a.condition_number, b.condition_number},
                      {a.reciprocal_condition_number, b.reciprocal_condition_number},
                      {a.effective_condition_number, b.effective_condition_number},
                      {a.scaled_condition_number, b.scaled_condition_number}, {a.residual_norm, b.residual_norm}}) {
    EXPECT_TRUE(same(x, y)) << x << " vs " << y;
  }
  EXPECT_TRUE(same_matrix(a.singular_values, b.singular_values));
  EXPECT_TRUE(same_matrix(a.scaled_singular_values, b.scaled_singular_values));
  EXPECT_TRUE(same_matrix(a.solution, b.solution));
  EXPECT_TRUE(same_matrix(a.null_space, b.null_space));
  EXPECT_TRUE(same_matrix(a.range, b.range));
  EXPECT_EQ(a.explanation, b.explanation);
  EXPECT_EQ(a.warnings, b.warnings);
  ASSERT_EQ(a.columns.size(), b.columns.size());
  for (std::size_t j = 0; j < a.columns.size(); ++j) {
    const ColumnClassification &x = a.columns[j], &y = b.columns[j];
    EXPECT_EQ(std::tie(x.consistent, x.finite_solution_dimension, x.at_infinity_dimension, x.augmented_rank),
              std::tie(y.consistent, y.finite_solution_dimension, y.at_infinity_dimension, y.augmented_rank));
    EXPECT_TRUE(same(x.residual_norm, y.residual_norm) && same(x.backward_error, y.backward_error));
  }
}

TEST(RenderJson, LinearSystemResultsRoundTrip) {
  Generator g(8);
  const MatrixXd rank2 = g.gaussian(7, 2) * g.gaussian(2, 4);
  const std::vector<std::pair<MatrixXd, MatrixXd>> systems = {
      {g.gaussian(7, 4), g.gaussian(7, 3)},                     // full rank, 3 right-hand sides
      {g.gaussian(7, 4), g.gaussian(7, 1)},                     // one
      {rank2, g.gaussian(7, 2)},                                // rank-deficient
      {g.gaussian(3, 5), g.gaussian(3, 1)},                     // underdetermined
      {MatrixXd::Zero(3, 2), g.gaussian(3, 1)},                 // rank 0: no range
      {MatrixXd::Identity(2, 2) * 1e-300, MatrixXd::Constant(2, 1, 1e300)},  // a failure
  };
  for (const auto& [A, B] : systems) {
    const LinearSystemResult r = solve(A, B);
    SCOPED_TRACE(r.explanation);
    expect_same(from_json<LinearSystemResult>(to_json(r, JsonStyle::Exact)), r);
    EXPECT_TRUE(same_matrix(from_json<ColumnClassification>(to_json(r.columns[0], JsonStyle::Exact)).residual_norm *
                                MatrixXd::Ones(1, 1),
                            r.columns[0].residual_norm * MatrixXd::Ones(1, 1)));
  }
  EXPECT_FALSE(solve(systems.back().first, systems.back().second).ok());
}

TEST(RenderJson, AHexapodIdentificationRoundTrips) {
  const auto [A, B] = hexapod_data(24, 9);
  hexapod::IdentifyOptions options;
  options.truth = hexapod::thesis_mass_matrix();
  options.stiffness = MatrixXd::Identity(6, 6) * 1e4;
  options.fit.bootstrap = 12;
  options.fit.threads = 1;
  for (const hexapod::MethodIdentification& m : hexapod::identify(A, B, options)) {
    SCOPED_TRACE(std::string(to_string(m.result.method)));
    const auto back = from_json<hexapod::MethodIdentification>(hexapod::to_json(m, JsonStyle::Exact));
    expect_same(back.result, m.result);
    expect_same(back.error_vs_truth, m.error_vs_truth, "error_vs_truth");
    ASSERT_EQ(back.eigenvalues.has_value(), m.eigenvalues.has_value());
    if (m.eigenvalues) {
      EXPECT_TRUE(same_matrix(*back.eigenvalues, *m.eigenvalues));
    }
    ASSERT_EQ(back.modes_hz.has_value(), m.modes_hz.has_value());
    if (m.modes_hz) {
      EXPECT_TRUE(same_matrix(*back.modes_hz, *m.modes_hz));
    }
    ASSERT_EQ(back.modes_uncertainty.has_value(), m.modes_uncertainty.has_value());
    if (m.modes_uncertainty) expect_same(*back.modes_uncertainty, *m.modes_uncertainty);
  }
}

TEST(RenderJson, BadTextIsRefusedNamingTheClassAndTheField) {
  const auto message = [](auto read) -> std::string {
    try {
      read();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message([] { from_json<FitResult>("{not json"); }), "FitResult: the text is not JSON");
  EXPECT_EQ(message([] { from_json<FitResult>("[1, 2]"); }), "FitResult: the JSON is not an object");
  const auto [A, B] = hexapod_data(20, 3);
  std::string text = to_json(fit(A, B, Method::Spde), JsonStyle::Exact);
  const std::string x = "\"X\":";
  std::string no_x = text;
  no_x.replace(no_x.find(x), x.size(), "\"Y\":");
  EXPECT_EQ(message([&] { from_json<FitResult>(no_x); }), "FitResult: the JSON has no 'X'");
  std::string bad_method = text;
  bad_method.replace(bad_method.find("\"spde\""), 6, "\"nope\"");
  EXPECT_EQ(message([&] { from_json<FitResult>(bad_method); }), "FitResult: unknown method 'nope'");
  std::string bad_number = text;
  const std::string residual = "\"residual_norm\":";
  bad_number.insert(bad_number.find(residual) + residual.size(), "\"many\",\"ignored\":");
  EXPECT_EQ(message([&] { from_json<FitResult>(bad_number); }),
            "FitResult diagnostics 'residual_norm': expected a number, not \"many\"");
}

// ---- compare: the error against a truth --------------------------------------------------------

TEST(Compare, ErrorsAreTheFrobeniusDistanceOfEachSuccessfulEstimate) {
  const auto [A, B] = hexapod_data(30, 12);
  const MatrixXd truth = hexapod::thesis_mass_matrix();
  const Comparison c = compare(A, B, {}, truth);
  ASSERT_EQ(c.results.size(), kAllMethods.size());
  ASSERT_EQ(c.errors.size(), c.results.size());
  EXPECT_EQ(std::tie(c.m, c.n, c.d), std::make_tuple(Eigen::Index{30}, Eigen::Index{6}, Eigen::Index{6}));
  std::optional<std::size_t> best;
  for (std::size_t k = 0; k < c.results.size(); ++k) {
    ASSERT_TRUE(c.results[k].ok());
    // The definition, summed entry by entry.
    double sum = 0.0;
    for (Eigen::Index i = 0; i < truth.size(); ++i) sum += std::pow(c.results[k].X.data()[i] - truth.data()[i], 2);
    EXPECT_NEAR(*c.errors[k], std::sqrt(sum), 1e-12 * std::sqrt(sum));
    if (!best || *c.errors[k] < *c.errors[*best]) best = k;
  }
  EXPECT_EQ(closest_to_truth(c.errors), best);
  EXPECT_FALSE(closest_to_truth({std::nullopt, std::nullopt}).has_value());
  EXPECT_EQ(closest_to_truth({std::nullopt, 2.0, 1.0, 1.0}), std::optional<std::size_t>(2));
  // Without a truth: no errors; a failed method has none either.
  for (const auto& e : compare(A, B).errors) EXPECT_FALSE(e.has_value());
  FitResult failed;
  failed.status = Status::NumericalFailure;
  EXPECT_FALSE(error_vs_truth(failed, truth).has_value());
  EXPECT_THROW(compare(A, B, {}, MatrixXd::Identity(5, 5)), std::invalid_argument);
  EXPECT_THROW(error_vs_truth(c.results[0], MatrixXd::Identity(5, 6)), std::invalid_argument);
}

TEST(Compare, HexapodIdentifyUsesTheSameError) {
  const auto [A, B] = hexapod_data(30, 13);
  hexapod::IdentifyOptions options;
  options.truth = hexapod::thesis_mass_matrix();
  const Comparison c = compare(A, B, options.fit, options.truth);
  const std::vector<hexapod::MethodIdentification> methods = hexapod::identify(A, B, options);
  ASSERT_EQ(methods.size(), c.results.size());
  for (std::size_t k = 0; k < methods.size(); ++k) {
    EXPECT_EQ(methods[k].result.method, c.results[k].method);
    EXPECT_EQ(methods[k].error_vs_truth, c.errors[k]);
  }
}

// ---- reports -----------------------------------------------------------------------------------

TEST(Report, FitReportNamesTheFrontEndsMeansAndAFailure) {
  const auto [A, B] = hexapod_data(20, 14);
  const FitResult r = fit(A, B, Method::Spde);
  const std::string text = report(r, ReportHints{"BOOTSTRAP-HINT", "DETAILS-HINT"});
  EXPECT_EQ(text.rfind("spde estimate of X (6 x 6) from m = 20 rows\nX (no standard errors: BOOTSTRAP-HINT)\n", 0),
            0u)
      << text;
  EXPECT_NE(report(r).find("set `bootstrap` to N"), std::string::npos);
  MatrixXd rank1(3, 2);
  rank1 << 1, 2, 2, 4, 3, 6;
  const FitResult failed = fit(rank1, rank1, Method::Spde);
  EXPECT_EQ(report(failed), "spde estimate of X (2 x 2) from m = 3 rows\nfailed: " + failed.message + "\n");
}

}  // namespace
}  // namespace spdfit
