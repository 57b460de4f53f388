// Random draws std::mt19937_64's sequence lazily (detail::LazyMt19937_64): the same bits as the
// standard engine, at every length and across the points where the lazy seeding and the
// twisting change regime (156 and 312 words), and engine() continues the same sequence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "spdfit/random.hpp"

namespace {

using spdfit::Random;

double reference_uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

TEST(Random, LazyEngineDrawsTheStandardSequence) {
  for (const std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{5489},
                                   std::uint64_t{0xFFFFFFFFFFFFFFFFULL}, spdfit::trial_seed(3, 17)}) {
    spdfit::detail::LazyMt19937_64 lazy(seed);
    std::mt19937_64 reference(seed);
    for (int k = 0; k < 2000; ++k) ASSERT_EQ(lazy(), reference()) << "seed " << seed << ", draw " << k;
    EXPECT_EQ(lazy.drawn(), 2000U);
  }
}

TEST(Random, UniformIsTheTopBitsOfTheStandardEngine) {
  Random random(42);
  std::mt19937_64 reference(42);
  for (int k = 0; k < 700; ++k) ASSERT_EQ(random.uniform(), reference_uniform(reference)) << k;
}

TEST(Random, EngineContinuesTheSequenceAtAnyPoint) {
  for (const int before : {0, 1, 155, 156, 157, 311, 312, 313, 700}) {
    Random random(7);
    std::mt19937_64 reference(7);
    for (int k = 0; k < before; ++k) ASSERT_EQ(random.uniform(), reference_uniform(reference));
    std::mt19937_64& engine = random.engine();
    EXPECT_EQ(&engine, &random.engine());  // one engine, however often asked
    // Draws from the engine and from the source interleave into the one sequence.
    for (int k = 0; k < 400; ++k) {
      if (k % 3 == 0) {
        ASSERT_EQ(engine(), reference()) << "after " << before << ", draw " << k;
      } else {
        ASSERT_EQ(random.uniform(), reference_uniform(reference)) << "after " << before << ", draw " << k;
      }
    }
  }
}

TEST(Random, CopiesContinueIndependently) {
  Random a(11);
  for (int k = 0; k < 200; ++k) a.uniform();
  Random b = a;
  std::vector<double> from_a, from_b;
  for (int k = 0; k < 300; ++k) from_a.push_back(a.uniform());
  for (int k = 0; k < 300; ++k) from_b.push_back(b.uniform());
  EXPECT_EQ(from_a, from_b);
}

TEST(Random, NormalIsBoxMullerOnTheStandardSequence) {
  Random random(3);
  std::mt19937_64 reference(3);
  for (int k = 0; k < 50; ++k) {
    const double u1 = 1.0 - reference_uniform(reference), u2 = reference_uniform(reference);
    const double radius = std::sqrt(-2.0 * std::log(u1)), angle = 6.283185307179586476925286766559 * u2;
    ASSERT_EQ(random.normal(), radius * std::cos(angle)) << k;
    ASSERT_EQ(random.normal(), radius * std::sin(angle)) << k;
  }
}

}  // namespace
