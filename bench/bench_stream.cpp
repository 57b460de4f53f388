// Throughput of the streaming fit (spdfit fit --stream): stream_factor over two data files of
// m x 6 rows written once to the temporary directory, as .npy (read block by block) and as CSV
// (parsed as read), on 1 and 2 threads. Reports bytes of both files per second; hold it
// against the time `cat A B > /dev/null` takes to read the same files from the page cache
// (bench/results/ records both). The in-memory reader is the baseline: io::read_matrix of both
// files plus TriangularFactor::from_data.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <random>
#include <string>

#include "spdfit/io.hpp"
#include "spdfit/stream.hpp"

namespace {

namespace fs = std::filesystem;
using Eigen::Index;
using Eigen::MatrixXd;

constexpr Index kRows = 1'000'000;
constexpr Index kCols = 6;

struct Files {
  std::string a, b;
  double bytes = 0;
};

// The data files, written on first use: A noisy, B = A X + noise.
const Files& files(const std::string& extension) {
  static std::map<std::string, Files> made;
  auto it = made.find(extension);
  if (it != made.end()) return it->second;
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal;
  const MatrixXd A = MatrixXd::NullaryExpr(kRows, kCols, [&] { return normal(engine); });
  const MatrixXd X = MatrixXd::Identity(kCols, kCols) * 3.0 + MatrixXd::Constant(kCols, kCols, 0.5);
  const MatrixXd B = A * X + 0.1 * MatrixXd::NullaryExpr(kRows, kCols, [&] { return normal(engine); });
  const fs::path dir = fs::temp_directory_path();
  Files f{(dir / ("spdfit_bench_A" + extension)).string(), (dir / ("spdfit_bench_B" + extension)).string()};
  if (extension == ".npy") {
    spdfit::io::write_npy(f.a, A);
    spdfit::io::write_npy(f.b, B);
  } else {
    spdfit::io::write_csv(f.a, A);
    spdfit::io::write_csv(f.b, B);
  }
  f.bytes = static_cast<double>(fs::file_size(f.a) + fs::file_size(f.b));
  return made.emplace(extension, f).first->second;
}

void BM_Stream(benchmark::State& state, const std::string& extension) {
  const Files& f = files(extension);
  spdfit::StreamOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    spdfit::TriangularFactor factor = spdfit::stream_factor(f.a, f.b, options);
    benchmark::DoNotOptimize(factor.R().data());
  }
  state.counters["bytes"] =
      benchmark::Counter(f.bytes * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_InMemory(benchmark::State& state, const std::string& extension) {
  const Files& f = files(extension);
  for (auto _ : state) {
    const MatrixXd A = spdfit::io::read_matrix(f.a);
    const MatrixXd B = spdfit::io::read_matrix(f.b);
    spdfit::TriangularFactor factor = spdfit::TriangularFactor::from_data(A, B);
    benchmark::DoNotOptimize(factor.R().data());
  }
  state.counters["bytes"] =
      benchmark::Counter(f.bytes * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Stream, npy, std::string(".npy"))
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Stream, csv, std::string(".csv"))
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_InMemory, npy, std::string(".npy"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_InMemory, csv, std::string(".csv"))->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
