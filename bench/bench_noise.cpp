// The cost of a noise model: spd-tls with one (the maximum-likelihood estimate) against spd-tls
// without (equal noise), both from the same Reduction, on the noise-model table's data (the
// thesis' hexapod, 6 x 6, per-channel Gaussian noise, m = 100 and 1000); the rest segment's
// covariances (2000 rows, in memory and from CSV files); and fit_files with and without the rest
// files (the library's share of `spdfit fit --rest-a ... --rest-b ...`).
//
//   build/bench/spdfit_bench_noise --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/io.hpp"
#include "spdfit/noise_model.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;


spdfit::hexapod::SimulationOptions table_options(Index m) {
  spdfit::hexapod::SimulationOptions options;
  options.samples = m;
  options.distribution = spdfit::hexapod::NoiseDistribution::Gaussian;
  VectorXd std_a(6), std_b(6);
  std_a << 0.2, 0.4, 0.8, 0.2, 0.4, 0.8;
  std_b << 3.0, 1.0, 0.3, 3.0, 1.0, 0.3;
  options.noise_std_a = std_a;
  options.noise_std_b = std_b;
  options.rest_samples = 2000;
  return options;
}

spdfit::hexapod::Measurements table_data(Index m) {
  return spdfit::hexapod::simulate(spdfit::hexapod::thesis_mass_matrix(), table_options(m), std::uint64_t{1});
}

// spd-tls from the reduction, with the true covariances (`with_model`) or without a model.
void BM_SpdTls(benchmark::State& state, bool with_model) {
  const spdfit::hexapod::Measurements data = table_data(state.range(0));
  spdfit::FitOptions options;
  if (with_model) options.noise = spdfit::hexapod::true_noise_model(table_options(state.range(0)), 6);
  const spdfit::Reduction reduced = spdfit::reduce(spdfit::TriangularFactor::from_data(data.A, data.B), options);
  int iterations = 0;
  for (auto _ : state) {
    spdfit::FitResult result = spdfit::fit(reduced, spdfit::Method::SpdTotalLeastSquares);
    iterations = result.diagnostics.iterations.value_or(-1);
    benchmark::DoNotOptimize(result.X.data());
  }
  state.counters["newton_steps"] = iterations;
}

void BM_RestCovariance(benchmark::State& state) {
  const spdfit::hexapod::Measurements data = table_data(100);
  for (auto _ : state) {
    spdfit::NoiseModel model = spdfit::NoiseModel::from_rest(data.rest_A, data.rest_B);
    benchmark::DoNotOptimize(model.cov_a().data());
  }
}

// Files in a scratch folder, written once.
struct Files {
  std::string a, b, rest_a, rest_b;
  Files() {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "spdfit_bench_noise";
    std::filesystem::create_directories(dir);
    const spdfit::hexapod::Measurements data = table_data(1000);
    a = (dir / "A.csv").string();
    b = (dir / "B.csv").string();
    rest_a = (dir / "rest_A.csv").string();
    rest_b = (dir / "rest_B.csv").string();
    spdfit::io::write_csv(a, data.A);
    spdfit::io::write_csv(b, data.B);
    spdfit::io::write_csv(rest_a, data.rest_A);
    spdfit::io::write_csv(rest_b, data.rest_B);
  }
};
const Files& files() {
  static const Files f;
  return f;
}

void BM_RestCovarianceFromFiles(benchmark::State& state) {
  const Files& f = files();
  for (auto _ : state) {
    spdfit::NoiseModel model = spdfit::NoiseModel::from_rest_files(f.rest_a, f.rest_b);
    benchmark::DoNotOptimize(model.cov_a().data());
  }
}

// fit_files on 1000 rows of CSV with auto: without a model, and with the rest files' model (read
// each time, as a command would).
void BM_FitFiles(benchmark::State& state, bool with_rest) {
  const Files& f = files();
  for (auto _ : state) {
    spdfit::FitOptions options;
    if (with_rest) options.noise = spdfit::NoiseModel::from_rest_files(f.rest_a, f.rest_b);
    spdfit::FitResult result = spdfit::fit_files(f.a, f.b, spdfit::Method::Auto, options);
    benchmark::DoNotOptimize(result.X.data());
  }
}

BENCHMARK_CAPTURE(BM_SpdTls, equal_noise, false)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SpdTls, noise_model, true)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RestCovariance)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RestCovarianceFromFiles)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FitFiles, no_model, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FitFiles, rest_files, true)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
