#include "spdfit/random.hpp"

#include <cmath>

namespace spdfit {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// One SplitMix64 step: the state advances by the golden-ratio increment and the output is
// the state through Stafford's "Mix13" finalizer.
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t trial_seed(std::uint64_t seed, std::uint64_t trial) {
  // Mix the seed first and add the trial to the mixed value, then mix again: (seed, trial)
  // and (seed + 1, trial - 1) must not collide, which a plain seed + trial would allow.
  std::uint64_t state = seed;
  std::uint64_t mixed = splitmix64(state) + trial;
  return splitmix64(mixed);
}

std::mt19937_64& Random::engine() {
  if (!engine_) {
    engine_.emplace(seed_);
    engine_->discard(lazy_.drawn());
  }
  return *engine_;
}

double Random::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // u1 in (0, 1] so that log(u1) is finite.
  const double u1 = 1.0 - uniform();
  const double u2 = uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = kTwoPi * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

}  // namespace spdfit
