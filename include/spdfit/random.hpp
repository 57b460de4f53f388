// Reproducible random numbers for simulations and Monte Carlo experiments.
#pragma once

#include <cstdint>
#include <random>

namespace spdfit {

/// The seed of trial `trial` of an experiment seeded with `seed`: two rounds of SplitMix64
/// (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", 2014) over the
/// pair, so that neighbouring trials and neighbouring seeds get unrelated streams. Every trial
/// draws from its own generator seeded with this value, which makes an experiment's numbers
/// independent of how its trials are spread over threads.
std::uint64_t trial_seed(std::uint64_t seed, std::uint64_t trial);

/// A random source: std::mt19937_64 (whose output sequence the C++ standard fixes) with
/// uniform and normal draws computed here rather than by std::uniform_real_distribution and
/// std::normal_distribution, whose algorithms differ between standard libraries.
///
/// Reproducibility: uniform() depends on nothing but the seed. normal() uses the Box-Muller
/// transform, so it also depends on std::log, std::sqrt, std::cos and std::sin; the numbers
/// are therefore identical for a given build (compiler, libstdc++ and libm), and may differ in
/// the last bits on another platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Uniform on [0, 1): the top 53 bits of one 64-bit draw, times 2^-53 (exact).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Standard normal (mean 0, variance 1), by the Box-Muller transform; draws come in pairs,
  /// the second of a pair is kept for the next call.
  double normal();

  /// The underlying engine, for callers that need raw 64-bit draws.
  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace spdfit
