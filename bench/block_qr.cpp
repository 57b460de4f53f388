// The streaming block QR (issue 19, item 4): the R of one block of rows of [A B], m = 32768 rows
// (StreamOptions' default block) by k = n + d = 12, 40 and 100 columns (n = 6, 20, 50), on one
// thread, as each streaming thread runs it:
//   BM_BlockQr/<isa>/k:       spdfit's block QR (detail::absorb_into_triangle) on each
//                             instruction set this CPU runs (baseline, avx2, avx512);
//   BM_Dgeqrf/k:              LAPACK's dgeqrf (Debian's OpenBLAS, one thread), the rate the issue
//                             holds the block QR against (target: at least 70% of it);
//   BM_EigenHouseholder/k:    Eigen's HouseholderQR, what the block QR replaced below 64 columns.
// Counters: GFLOP/s at 2 m k^2 - 2 k^3 / 3 flops per QR (LAPACK's count for dgeqrf).
// Run: build/bench/spdfit_block_qr --benchmark_min_time=0.2
#include <benchmark/benchmark.h>
#include <lapacke.h>

#include <Eigen/QR>
#include <string>

#include "numerics/blas_core.hpp"
#include "numerics/block_qr.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using spdfit::detail::VectorIsa;

constexpr Index kBlockRows = Index{1} << 15;

MatrixXd block(Index k) {
  std::srand(1);
  return MatrixXd::Random(kBlockRows, k);
}

void set_rate(benchmark::State& state, Index k) {
  const double m = static_cast<double>(kBlockRows), n = static_cast<double>(k);
  state.counters["GFLOP/s"] = benchmark::Counter((2 * m * n * n - 2 * n * n * n / 3) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

void BM_BlockQr(benchmark::State& state, VectorIsa isa) {
  if (isa > spdfit::detail::cpu_vector_isa()) {
    state.SkipWithError("this CPU lacks the instruction set");
    return;
  }
  const Index k = state.range(0);
  const MatrixXd A = block(k);
  MatrixXd C(A.rows(), k), R(k, k);
  for (auto _ : state) {
    C = A;
    R.setZero();
    spdfit::detail::absorb_into_triangle(isa, R, C);
    benchmark::DoNotOptimize(R.data());
  }
  set_rate(state, k);
}

void BM_Dgeqrf(benchmark::State& state) {
  spdfit::detail::set_blas_threads(1);
  const Index k = state.range(0);
  const MatrixXd A = block(k);
  MatrixXd C(A.rows(), k);
  Eigen::VectorXd tau(k);
  for (auto _ : state) {
    C = A;
    LAPACKE_dgeqrf(LAPACK_COL_MAJOR, static_cast<lapack_int>(C.rows()), static_cast<lapack_int>(k), C.data(),
                   static_cast<lapack_int>(C.rows()), tau.data());
    benchmark::DoNotOptimize(C.data());
  }
  set_rate(state, k);
}

void BM_EigenHouseholder(benchmark::State& state) {
  const Index k = state.range(0);
  const MatrixXd A = block(k);
  MatrixXd C(A.rows(), k);
  for (auto _ : state) {
    C = A;
    const Eigen::HouseholderQR<Eigen::Ref<MatrixXd>> qr(C);
    benchmark::DoNotOptimize(C.data());
  }
  set_rate(state, k);
}

}  // namespace

BENCHMARK_CAPTURE(BM_BlockQr, baseline, VectorIsa::Baseline)->Arg(12)->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BlockQr, avx2, VectorIsa::Avx2)->Arg(12)->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BlockQr, avx512, VectorIsa::Avx512)->Arg(12)->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dgeqrf)->Arg(12)->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EigenHouseholder)->Arg(12)->Arg(40)->Arg(100)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
