// Speed of physical identification (hexapod::identify_physical) on the thesis' set-up: the built-in
// hexapod, uniform noise of width 3.2 in A and B, the geometry's strut masses. One fit from A and B
// (the factor of [A B] included) at m = 12, 100 and 1000, for the nominal payload (its minimum
// inside the cone of consistent payloads) and a thin rod (its minimum on the boundary); and the
// bootstrap of 1000 replicates at m = 1000 on 1 and 2 threads. The generic spd-tls fit of the same
// data (spdfit::fit) is the baseline: what a user of the generic estimator pays.
#include <benchmark/benchmark.h>

#include "spdfit/fit.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/simulate.hpp"

namespace {

using namespace spdfit;

RigidBodyInertia thin_rod() {
  RigidBodyInertia rod;
  rod.mass = 11.973;
  const double length = 0.45, thickness = 0.0045;
  const double across = rod.mass * thickness * thickness / 12.0, along = rod.mass * length * length / 12.0;
  rod.inertia = Eigen::Vector3d(2 * across, along + across, along + across).asDiagonal();
  return rod;
}

hexapod::Measurements data(Eigen::Index m, bool rod) {
  const hexapod::Geometry geometry = hexapod::cubic_geometry();
  hexapod::SimulationOptions simulation;
  simulation.samples = m;
  simulation.noise_var = 3.2 * 3.2 / 12.0;
  return hexapod::simulate(geometry, rod ? thin_rod() : hexapod::nominal_payload(geometry), simulation, 1);
}

void BM_PhysicalFit(benchmark::State& state) {
  const hexapod::Measurements d = data(state.range(0), state.range(1) != 0);
  const hexapod::Geometry geometry = hexapod::cubic_geometry();
  int iterations = 0;
  for (auto _ : state) {
    const hexapod::PhysicalEstimate e = hexapod::identify_physical(d.A, d.B, geometry);
    iterations = e.iterations;
    benchmark::DoNotOptimize(e.M_p.data());
  }
  state.counters["newton_steps"] = iterations;
}
BENCHMARK(BM_PhysicalFit)
    ->ArgNames({"m", "rod"})
    ->Args({12, 0})
    ->Args({100, 0})
    ->Args({1000, 0})
    ->Args({12, 1})
    ->Args({100, 1})
    ->Args({1000, 1})
    ->Unit(benchmark::kMicrosecond);

void BM_SpdTlsFit(benchmark::State& state) {
  const hexapod::Measurements d = data(state.range(0), false);
  for (auto _ : state) {
    const FitResult r = fit(d.A, d.B, Method::SpdTotalLeastSquares);
    benchmark::DoNotOptimize(r.X.data());
  }
}
BENCHMARK(BM_SpdTlsFit)->ArgName("m")->Arg(12)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_PhysicalBootstrap(benchmark::State& state) {
  const hexapod::Measurements d = data(1000, state.range(1) != 0);
  const hexapod::Geometry geometry = hexapod::cubic_geometry();
  hexapod::PhysicalOptions options;
  options.bootstrap = 1000;
  options.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    const hexapod::PhysicalEstimate e = hexapod::identify_physical(d.A, d.B, geometry, options);
    benchmark::DoNotOptimize(e.bootstrap->M_p.standard_errors.data());
  }
}
BENCHMARK(BM_PhysicalBootstrap)
    ->ArgNames({"threads", "rod"})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
