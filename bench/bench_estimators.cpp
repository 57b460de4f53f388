// Time per estimate of each method from the data A, B (m x n) to the FitResult with all its
// diagnostics, at n = 2, 6, 12 (m = 2n; n = 6, m = 12 is the thesis' hexapod problem),
// n = 100 and n = 1000 (m = 4n). The BM_Factor rows time the shared part alone (the
// Householder QR of [A B] and the reduction: SVD of R11, triangular factor and singular values
// of B), so method minus factor is the method's own cost; the BM_QR rows time the QR of [A B]
// alone and report its rate in floating-point operations per second ("flops", counting the
// 2 k^2 (m - k/3) flops of a Householder QR of an m x k matrix, k = 2n), a figure to hold
// against the machine's peak. The other rows have no flop count: their iterative SVDs and
// eigensolvers take a data-dependent number of sweeps. The same estimators in NumPy/SciPy are
// timed by bench/compare.py. The n = 1000 rows take seconds each; --benchmark_filter=-/4000/
// skips them. BM_Fit leaves the noise estimate unread (a fit computes it when it is read);
// BM_FitNoise reads it.
#include <benchmark/benchmark.h>

#include <Eigen/QR>
#include <random>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/fit.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;

struct Data {
  MatrixXd A, B;
};

Data make_data(Index m, Index n) {
  std::mt19937_64 engine(42);
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  auto random = [&](Index rows, Index cols) {
    return MatrixXd::NullaryExpr(rows, cols, [&]() { return uniform(engine); });
  };
  const MatrixXd W = random(n, n);
  const MatrixXd X = W * W.transpose() + n * MatrixXd::Identity(n, n);
  const MatrixXd A0 = random(m, n);
  return {A0 + 0.3 * random(m, n), A0 * X + 0.3 * random(m, n)};
}

// Data whose truth is indefinite (eigenvalues spread over [-n/4, 3n/4]): symmetric Procrustes is
// then indefinite and psd-ls has to iterate (on make_data it returns Procrustes at once).
Data make_indefinite_data(Index m, Index n) {
  std::mt19937_64 engine(43);
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  auto random = [&](Index rows, Index cols) {
    return MatrixXd::NullaryExpr(rows, cols, [&]() { return uniform(engine); });
  };
  const Eigen::HouseholderQR<MatrixXd> qr(random(n, n));
  const MatrixXd Q = qr.householderQ();
  Eigen::VectorXd lambda(n);
  for (Index i = 0; i < n; ++i) lambda(i) = static_cast<double>(i) - 0.25 * static_cast<double>(n);
  const MatrixXd X = Q * lambda.asDiagonal() * Q.transpose();
  const MatrixXd A0 = random(m, n);
  return {A0 + 0.3 * random(m, n), A0 * X + 0.3 * random(m, n)};
}

// Floating-point operations of the Householder QR of the m x 2n matrix [A B] (R only, no Q).
double qr_flops(Index m, Index n) {
  const double k = 2.0 * static_cast<double>(n);
  return 2.0 * k * k * (static_cast<double>(m) - k / 3.0);
}

void BM_Fit(benchmark::State& state, spdfit::Method method) {
  const Data data = make_data(state.range(0), state.range(1));
  for (auto _ : state) {
    spdfit::FitResult result = spdfit::fit(data.A, data.B, method);
    benchmark::DoNotOptimize(result.X.data());
  }
}

// fit() with the noise estimate read as well (Diagnostics::noise_sigma), as --json, --report and
// Python's attribute read it: a fit computes the noise estimate only when it is read, so BM_Fit
// times X with the other diagnostics and BM_FitNoise adds the noise estimate's SVD.
void BM_FitNoise(benchmark::State& state, spdfit::Method method) {
  const Data data = make_data(state.range(0), state.range(1));
  for (auto _ : state) {
    spdfit::FitResult result = spdfit::fit(data.A, data.B, method);
    const double sigma = result.diagnostics.noise_sigma.value_or(0.0);
    benchmark::DoNotOptimize(sigma);
    benchmark::DoNotOptimize(result.X.data());
  }
}

// One method's X alone, as the Monte Carlo experiments compute it (experiment::estimate: no
// diagnostics; n <= 8 on stack matrices with no heap allocation per call).
void BM_Estimate(benchmark::State& state, spdfit::Method method) {
  const Data data = make_data(state.range(0), state.range(1));
  const std::vector<spdfit::Method> methods = {method};
  std::vector<MatrixXd> X;
  for (auto _ : state) {
    spdfit::experiment::estimate(data.A, data.B, methods, X);
    benchmark::DoNotOptimize(X[0].data());
  }
}

// The method's own cost, from a Reduction made once (the iterative methods: spd-tls, psd-ls,
// auto). `indefinite` selects make_indefinite_data, where psd-ls's constraint is active.
void BM_FromReduction(benchmark::State& state, spdfit::Method method, bool indefinite) {
  const Data data = indefinite ? make_indefinite_data(state.range(0), state.range(1))
                               : make_data(state.range(0), state.range(1));
  const spdfit::Reduction reduced = spdfit::reduce(spdfit::TriangularFactor::from_data(data.A, data.B));
  for (auto _ : state) {
    spdfit::FitResult result = spdfit::fit(reduced, method);
    benchmark::DoNotOptimize(result.X.data());
  }
}

void BM_Factor(benchmark::State& state) {
  const Data data = make_data(state.range(0), state.range(1));
  for (auto _ : state) {
    spdfit::Reduction reduced = spdfit::reduce(spdfit::TriangularFactor::from_data(data.A, data.B));
    benchmark::DoNotOptimize(reduced.rank_b());
  }
}

void BM_QR(benchmark::State& state) {
  const Data data = make_data(state.range(0), state.range(1));
  for (auto _ : state) {
    spdfit::TriangularFactor factor = spdfit::TriangularFactor::from_data(data.A, data.B);
    benchmark::DoNotOptimize(factor.R().data());
  }
  state.counters["flops"] = benchmark::Counter(
      qr_flops(state.range(0), state.range(1)) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

// {m, n}: m = 2n for the small problems (the thesis' m = 12, n = 6 among them), m = 4n for the
// large ones.
void sizes(benchmark::internal::Benchmark* b) {
  b->Args({4, 2})->Args({12, 6})->Args({24, 12})->Args({400, 100})->Args({4000, 1000});
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_QR)->Apply(sizes);
BENCHMARK(BM_Factor)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, ls, spdfit::Method::LeastSquares)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, procrustes, spdfit::Method::SymmetricProcrustes)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, tls, spdfit::Method::TotalLeastSquares)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, tls_sym, spdfit::Method::TotalLeastSquaresSymmetric)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, tls_psd, spdfit::Method::TotalLeastSquaresPsd)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, spde, spdfit::Method::Spde)->Apply(sizes);

// Large n against the LAPACK floor (lapack_floor.cpp's BM_FloorFit and BM_FloorFitNoise, same
// m and n): m = 4000, n = 1000 and 2000. Each n = 2000 row takes tens of seconds.
void large_sizes(benchmark::internal::Benchmark* b) {
  b->Args({4000, 1000})->Args({4000, 2000})->Unit(benchmark::kMillisecond);
}
BENCHMARK_CAPTURE(BM_Fit, spde, spdfit::Method::Spde)->Args({4000, 2000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Fit, procrustes, spdfit::Method::SymmetricProcrustes)
    ->Args({4000, 2000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Fit, tls, spdfit::Method::TotalLeastSquares)->Args({4000, 2000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitNoise, spde, spdfit::Method::Spde)->Apply(large_sizes);
BENCHMARK_CAPTURE(BM_FitNoise, procrustes, spdfit::Method::SymmetricProcrustes)->Apply(large_sizes);
BENCHMARK_CAPTURE(BM_FitNoise, tls, spdfit::Method::TotalLeastSquares)->Apply(large_sizes);

// X alone: up to n = 8 the small-problem path, above it fit() without the diagnostics.
void estimate_sizes(benchmark::internal::Benchmark* b) {
  b->Args({4, 2})->Args({12, 6})->Args({24, 12})->Args({4000, 1000})->Args({8000, 2000});
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK_CAPTURE(BM_Estimate, ls, spdfit::Method::LeastSquares)->Apply(estimate_sizes);
BENCHMARK_CAPTURE(BM_Estimate, procrustes, spdfit::Method::SymmetricProcrustes)->Apply(estimate_sizes);
BENCHMARK_CAPTURE(BM_Estimate, tls, spdfit::Method::TotalLeastSquares)->Apply(estimate_sizes);
BENCHMARK_CAPTURE(BM_Estimate, spde, spdfit::Method::Spde)->Apply(estimate_sizes);

// The iterative methods (issue 14's targets: spd-tls and psd-ls at n = 6 under 50 us, psd-ls at
// n = 100 under 20 ms and n = 1000 under 10 s). BM_Estimate: X alone on the small-problem path.
void small_sizes(benchmark::internal::Benchmark* b) {
  b->Args({12, 6})->Args({100, 6})->Unit(benchmark::kMicrosecond);
}
BENCHMARK_CAPTURE(BM_Estimate, spd_tls, spdfit::Method::SpdTotalLeastSquares)->Apply(small_sizes);
BENCHMARK_CAPTURE(BM_Estimate, psd_ls, spdfit::Method::PsdLeastSquares)->Apply(small_sizes);
BENCHMARK_CAPTURE(BM_Estimate, auto, spdfit::Method::Auto)->Apply(small_sizes);
BENCHMARK_CAPTURE(BM_FromReduction, spd_tls, spdfit::Method::SpdTotalLeastSquares, false)
    ->Args({12, 6})->Args({24, 12})->Args({100, 20})->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FromReduction, psd_ls_indefinite, spdfit::Method::PsdLeastSquares, true)
    ->Args({12, 6})->Args({400, 100})->Args({4000, 1000})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FromReduction, auto, spdfit::Method::Auto, false)
    ->Args({12, 6})->Args({1000, 6})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
