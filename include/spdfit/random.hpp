// Reproducible random numbers for simulations and Monte Carlo experiments.
#pragma once

#include <cstdint>
#include <optional>
#include <random>

namespace spdfit {

/// The seed of trial `trial` of an experiment seeded with `seed`: two rounds of SplitMix64
/// (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", 2014) over the
/// pair, so that neighbouring trials and neighbouring seeds get unrelated streams. Every trial
/// draws from its own generator seeded with this value, which makes an experiment's numbers
/// independent of how its trials are spread over threads.
std::uint64_t trial_seed(std::uint64_t seed, std::uint64_t trial);

namespace detail {

/// std::mt19937_64's output sequence, computed lazily: the state is seeded and twisted one word
/// at a time as draws are taken, in the order the standard's block algorithm gives them, so the
/// numbers are the same bits. A trial that takes k < 156 draws seeds only k + 156 of the 312
/// words and twists only k of them, where std::mt19937_64 seeds and twists all 312 at its first
/// draw: the whole cost of a small Monte Carlo trial's random numbers.
class LazyMt19937_64 {
 public:
  static constexpr int kWords = 312, kShift = 156;

  explicit LazyMt19937_64(std::uint64_t seed) { x_[0] = seed; }

  std::uint64_t operator()() {
    if (seeded_ < kWords) seed_through(position_ < kWords - kShift ? position_ + kShift : kWords - 1);
    const int k = position_;
    const std::uint64_t next = x_[k + 1 < kWords ? k + 1 : 0];
    const std::uint64_t y = (x_[k] & kUpper) | (next & kLower);
    x_[k] = x_[k + kShift < kWords ? k + kShift : k + kShift - kWords] ^ (y >> 1) ^ ((y & 1U) ? kMatrix : 0U);
    position_ = k + 1 < kWords ? k + 1 : 0;
    ++drawn_;
    std::uint64_t z = x_[k];
    z ^= (z >> 29) & 0x5555555555555555ULL;
    z ^= (z << 17) & 0x71D67FFFEDA60000ULL;
    z ^= (z << 37) & 0xFFF7EEE000000000ULL;
    return z ^ (z >> 43);
  }

  /// How many words have been drawn.
  std::uint64_t drawn() const { return drawn_; }

 private:
  static constexpr std::uint64_t kUpper = ~std::uint64_t{0} << 31, kLower = ~kUpper;
  static constexpr std::uint64_t kMatrix = 0xB5026F5AA96619E9ULL;

  void seed_through(int last) {
    for (; seeded_ <= last; ++seeded_) {
      const std::uint64_t p = x_[seeded_ - 1];
      x_[seeded_] = 6364136223846793005ULL * (p ^ (p >> 62)) + static_cast<std::uint64_t>(seeded_);
    }
  }

  std::uint64_t x_[kWords];  // words at or above seeded_ are not yet set
  int seeded_ = 1;
  int position_ = 0;
  std::uint64_t drawn_ = 0;
};

}  // namespace detail

/// A random source: std::mt19937_64's sequence (which the C++ standard fixes), computed lazily
/// (detail::LazyMt19937_64), with uniform and normal draws computed here rather than by
/// std::uniform_real_distribution and std::normal_distribution, whose algorithms differ between
/// standard libraries.
///
/// Reproducibility: uniform() depends on nothing but the seed. normal() uses the Box-Muller
/// transform, so it also depends on std::log, std::sqrt, std::cos and std::sin; the numbers
/// are therefore identical for a given build (compiler, libstdc++ and libm), and may differ in
/// the last bits on another platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : seed_(seed), lazy_(seed) {}

  /// Uniform on [0, 1): the top 53 bits of one 64-bit draw, times 2^-53 (exact).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  /// Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Standard normal (mean 0, variance 1), by the Box-Muller transform; draws come in pairs,
  /// the second of a pair is kept for the next call.
  double normal();

  /// The underlying engine, for callers that need raw 64-bit draws: a std::mt19937_64 at the
  /// point of the sequence this source has reached. From the first call on, this source draws
  /// from it too, so draws taken from either continue one sequence.
  std::mt19937_64& engine();

 private:
  std::uint64_t next() { return engine_ ? (*engine_)() : lazy_(); }

  std::uint64_t seed_;
  detail::LazyMt19937_64 lazy_;
  std::optional<std::mt19937_64> engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace spdfit
