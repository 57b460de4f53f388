// The LAPACK floor of issue 6's goal 3: the work no estimator of X in A X ~= B (m x n, m = 4n)
// can avoid, done by LAPACK alone (Debian's OpenBLAS, the library spdfit links when built with
// SPDFIT_LAPACK), timed on the same data as bench_estimators:
//   BM_FloorSpde:  the QR of [A B] (dgeqrf, m x 2n) plus one symmetric eigendecomposition of
//                  size n (dsyevd, eigenvectors): the floor of spde and procrustes;
//   BM_FloorSpdeSvd: the same plus one n x n SVD with both vector sets (dgesdd on R11): issue 19's
//                  definition of that floor ("QR of [A B] + one n x n SVD + one symmetric
//                  eigendecomposition"), the stable path's own LAPACK work;
//   BM_FloorTls:   the QR of [A B] plus the SVD of its 2n x 2n triangular factor (dgesdd,
//                  right singular vectors): the floor of tls;
//   BM_FloorFit:   BM_FloorSpdeSvd for any m (arguments m, n): the floor of fit() with its
//                  diagnostics but the noise estimate, for spde and procrustes;
//   BM_FloorFitNoise: the same plus the values-only SVD (dgesdd, no vectors) of the 2n x 2n
//                  triangular factor: the floor of fit() with the noise estimate read;
// and the pieces alone (BM_Dgeqrf, BM_Dsyevd, BM_Dgesdd), so that each of spdfit's steps can
// be held against LAPACK's; BM_Dgemm (C = A B, n x n) shows which kernels OpenBLAS runs: its
// GFLOP/s against the same run with OPENBLAS_CORETYPE set is the number behind spdfit's choice of
// core (docs/performance.md, "The BLAS core"; bench/blas_core.sh runs it for every core). OpenBLAS
// picks its kernels and thread count itself (OPENBLAS_CORETYPE and OPENBLAS_NUM_THREADS override
// them); the run's context names the core ("openblas_core").
// Run: build/bench/spdfit_lapack_floor --benchmark_min_time=0.1
#include <benchmark/benchmark.h>
#include <lapacke.h>

#include <Eigen/Core>
#include <random>
#include <stdexcept>
#include <string>

// The Fortran BLAS's dgemm and OpenBLAS's name for its kernels (cblas.h declares them, but which
// cblas.h /usr/include holds depends on Debian's alternatives).
extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc);
extern "C" char* openblas_get_corename(void) __attribute__((weak));

namespace {

using Eigen::Index;
using Eigen::MatrixXd;

MatrixXd random_matrix(Index rows, Index cols, unsigned seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  return MatrixXd::NullaryExpr(rows, cols, [&]() { return uniform(engine); });
}

void check(lapack_int info, const char* routine) {
  if (info != 0) throw std::runtime_error(std::string(routine) + " failed");
}

// R of [A B] (m x 2n) by dgeqrf; returns the 2n x 2n triangle.
MatrixXd qr_factor(const MatrixXd& AB) {
  MatrixXd work = AB;
  Eigen::VectorXd tau(work.cols());
  check(LAPACKE_dgeqrf(LAPACK_COL_MAJOR, static_cast<lapack_int>(work.rows()), static_cast<lapack_int>(work.cols()),
                       work.data(), static_cast<lapack_int>(work.rows()), tau.data()),
        "dgeqrf");
  return work.topRows(work.cols()).triangularView<Eigen::Upper>();
}

void symmetric_eigen(MatrixXd S) {
  Eigen::VectorXd w(S.rows());
  check(LAPACKE_dsyevd(LAPACK_COL_MAJOR, 'V', 'U', static_cast<lapack_int>(S.rows()), S.data(),
                       static_cast<lapack_int>(S.rows()), w.data()),
        "dsyevd");
  benchmark::DoNotOptimize(w.data());
}

void right_singular_vectors(MatrixXd R) {
  const lapack_int n = static_cast<lapack_int>(R.rows());
  Eigen::VectorXd s(n);
  MatrixXd U(n, n), VT(n, n);
  check(LAPACKE_dgesdd(LAPACK_COL_MAJOR, 'S', n, n, R.data(), n, s.data(), U.data(), n, VT.data(), n), "dgesdd");
  benchmark::DoNotOptimize(VT.data());
}

void singular_values(MatrixXd R) {
  const lapack_int n = static_cast<lapack_int>(R.rows());
  Eigen::VectorXd s(n);
  double unused = 0.0;
  check(LAPACKE_dgesdd(LAPACK_COL_MAJOR, 'N', n, n, R.data(), n, s.data(), &unused, 1, &unused, 1), "dgesdd");
  benchmark::DoNotOptimize(s.data());
}

MatrixXd data(Index n) { return random_matrix(4 * n, 2 * n, 42); }

void BM_Dgeqrf(benchmark::State& state) {
  const MatrixXd AB = data(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(qr_factor(AB).data());
  const double m = static_cast<double>(AB.rows()), k = static_cast<double>(AB.cols());
  state.counters["flops"] =
      benchmark::Counter(2.0 * k * k * (m - k / 3.0) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

// C = A B with n x n operands: 2 n^3 flops, the BLAS's best case.
void BM_Dgemm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const MatrixXd A = random_matrix(n, n, 1), B = random_matrix(n, n, 2);
  MatrixXd C(n, n);
  const double one = 1.0, zero = 0.0;
  for (auto _ : state) {
    dgemm_("N", "N", &n, &n, &n, &one, A.data(), &n, B.data(), &n, &zero, C.data(), &n);
    benchmark::DoNotOptimize(C.data());
  }
  const double size = static_cast<double>(n);
  state.counters["flops"] = benchmark::Counter(
      2.0 * size * size * size * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Dsyevd(benchmark::State& state) {
  const MatrixXd W = random_matrix(state.range(0), state.range(0), 7);
  const MatrixXd S = W.transpose() * W;
  for (auto _ : state) symmetric_eigen(S);
}

void BM_Dgesdd(benchmark::State& state) {
  const MatrixXd R = qr_factor(data(state.range(0) / 2));  // 2n' x 2n' triangle, 2n' = range
  for (auto _ : state) right_singular_vectors(R);
}

// with_svd: issue 19's floor (BM_FloorSpdeSvd), with the n x n SVD of R11.
void floor_spde(benchmark::State& state, bool with_svd) {
  const Index n = state.range(0);
  const MatrixXd AB = data(n);
  const MatrixXd W = random_matrix(n, n, 7);
  const MatrixXd S = W.transpose() * W;
  for (auto _ : state) {
    const MatrixXd R = qr_factor(AB);
    benchmark::DoNotOptimize(R.data());
    if (with_svd) right_singular_vectors(R.topLeftCorner(n, n));
    symmetric_eigen(S);
  }
}

// BM_FloorFit (noise = false) and BM_FloorFitNoise: QR of the m x 2n [A B], the n x n SVD of R11
// with vectors, an n x n dsyevd, and with `noise` the values-only SVD of the 2n x 2n factor.
void floor_fit(benchmark::State& state, bool noise) {
  const Index m = state.range(0), n = state.range(1);
  const MatrixXd AB = random_matrix(m, 2 * n, 42);
  const MatrixXd W = random_matrix(n, n, 7);
  const MatrixXd S = W.transpose() * W;
  for (auto _ : state) {
    const MatrixXd R = qr_factor(AB);
    right_singular_vectors(R.topLeftCorner(n, n));
    symmetric_eigen(S);
    if (noise) singular_values(R);
  }
}

void BM_FloorFit(benchmark::State& state) { floor_fit(state, false); }
void BM_FloorFitNoise(benchmark::State& state) { floor_fit(state, true); }

void BM_FloorSpde(benchmark::State& state) { floor_spde(state, false); }
void BM_FloorSpdeSvd(benchmark::State& state) { floor_spde(state, true); }

void BM_FloorTls(benchmark::State& state) {
  const MatrixXd AB = data(state.range(0));
  for (auto _ : state) right_singular_vectors(qr_factor(AB));
}

void sizes(benchmark::internal::Benchmark* b) { b->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond); }

// Wall-clock time: OpenBLAS runs dgemm on its own threads, which this thread's CPU time misses.
BENCHMARK(BM_Dgemm)->Arg(1000)->Arg(2000)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dgeqrf)->Apply(sizes);
BENCHMARK(BM_Dsyevd)->Apply(sizes);
BENCHMARK(BM_Dgesdd)->Arg(2000)->Arg(4000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorSpde)->Apply(sizes);
BENCHMARK(BM_FloorSpdeSvd)->Apply(sizes);
BENCHMARK(BM_FloorTls)->Apply(sizes);
BENCHMARK(BM_FloorFit)->Args({4000, 1000})->Args({4000, 2000})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorFitNoise)->Args({4000, 1000})->Args({4000, 2000})->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("openblas_core",
                              openblas_get_corename ? openblas_get_corename() : "(not OpenBLAS)");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
