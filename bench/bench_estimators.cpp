// Time per estimate of each method on the thesis' problem size (n = 6, m = 12) and a larger one
// (n = 100, m = 1000), from the data A, B to the FitResult with all its diagnostics. The
// "factor" rows time the shared part alone (the Householder QR of [A B] and the reduction:
// SVD of R11, triangular factor and singular values of B), so method minus factor is the
// method's own cost. Reference points (NumPy, Octave) are measured by bench/compare.py.
#include <benchmark/benchmark.h>

#include <random>

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

void BM_Fit(benchmark::State& state, spdfit::Method method) {
  const Data data = make_data(state.range(0), state.range(1));
  for (auto _ : state) {
    spdfit::FitResult result = spdfit::fit(data.A, data.B, method);
    benchmark::DoNotOptimize(result.X.data());
  }
}

void BM_Factor(benchmark::State& state) {
  const Data data = make_data(state.range(0), state.range(1));
  for (auto _ : state) {
    spdfit::Reduction reduced = spdfit::reduce(spdfit::TriangularFactor::from_data(data.A, data.B));
    benchmark::DoNotOptimize(reduced.R_b.data());
  }
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({12, 6})->Args({1000, 100})->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_Factor)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, ls, spdfit::Method::LeastSquares)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, procrustes, spdfit::Method::SymmetricProcrustes)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, tls, spdfit::Method::TotalLeastSquares)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, tls_sym, spdfit::Method::TotalLeastSquaresSymmetric)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, tls_psd, spdfit::Method::TotalLeastSquaresPsd)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Fit, spde, spdfit::Method::Spde)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
