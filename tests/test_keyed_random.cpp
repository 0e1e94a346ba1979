// Protects the keyed random generator (geometry/keyed_random): Philox4x32-10 against the
// Random123 known-answer vectors, the independence of keys and purposes, and the moments of the
// uniform and normal draws every noise model relies on.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "geometry/keyed_random.hpp"

namespace owsim {
namespace {

// kat_vectors of the Random123 distribution, philox4x32_10 lines.
TEST(KeyedRandom, Philox4x32_10KnownAnswers) {
  EXPECT_EQ(philox4x32_10({0, 0, 0, 0}, {0, 0}),
            (PhiloxBlock{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}));
  EXPECT_EQ(philox4x32_10({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
                          {0xffffffffu, 0xffffffffu}),
            (PhiloxBlock{0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}));
  EXPECT_EQ(philox4x32_10({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u},
                          {0xa4093822u, 0x299f31d0u}),
            (PhiloxBlock{0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}));
}

constexpr std::array<RandomPurpose, 7> kPurposes = {
    RandomPurpose::frame_jitter,       RandomPurpose::range_noise_first,
    RandomPurpose::range_noise_second, RandomPurpose::range_noise_reference,
    RandomPurpose::irs_error,          RandomPurpose::irs_bias,
    RandomPurpose::forest_layout};

TEST(KeyedRandom, SameKeySameBlock) {
  const RandomKey key{42, 7, 1234, RandomPurpose::range_noise_first};
  EXPECT_EQ(random_block(key), random_block(key));
  EXPECT_EQ(uniform01(key), uniform01(key));
  EXPECT_EQ(standard_normal(key), standard_normal(key));
}

TEST(KeyedRandom, NoTwoPurposesOrKeysShareABlock) {
  std::set<PhiloxBlock> seen;
  std::size_t draws = 0;
  for (std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{1} << 32,
                             std::uint64_t{0xdeadbeefcafef00d}}) {
    for (std::int64_t frame : {std::int64_t{0}, std::int64_t{1}, std::int64_t{-1},
                               std::int64_t{1} << 32, std::int64_t{10'000}}) {
      for (std::int64_t pulse : {std::int64_t{0}, std::int64_t{1}, std::int64_t{20'351},
                                 std::int64_t{1} << 32, (std::int64_t{1} << 32) + 1}) {
        for (RandomPurpose purpose : kPurposes) {
          seen.insert(random_block(RandomKey{seed, frame, pulse, purpose}));
          ++draws;
        }
      }
    }
  }
  EXPECT_EQ(seen.size(), draws);
}

TEST(KeyedRandom, PurposeStreamsAreUncorrelated) {
  // Two purposes on the same (seed, frame, pulse): their uniforms must not track each other.
  constexpr int kDraws = 20'000;
  for (std::size_t a = 0; a < kPurposes.size(); ++a) {
    for (std::size_t b = a + 1; b < kPurposes.size(); ++b) {
      double sum_ab = 0.0;
      for (int i = 0; i < kDraws; ++i) {
        const double ua = uniform01(RandomKey{3, 5, i, kPurposes[a]}) - 0.5;
        const double ub = uniform01(RandomKey{3, 5, i, kPurposes[b]}) - 0.5;
        sum_ab += ua * ub;
      }
      // Correlation of independent uniforms: sd 1/√N; 4σ bound.
      const double correlation = (sum_ab / kDraws) * 12.0;
      EXPECT_LT(std::abs(correlation), 4.0 / std::sqrt(kDraws)) << a << " vs " << b;
    }
  }
}

struct Moments {
  double mean = 0.0;
  double variance = 0.0;
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (double v : x) m.variance += (v - m.mean) * (v - m.mean);
  m.variance /= static_cast<double>(x.size() - 1);
  return m;
}

constexpr int kSamples = 100'000;

TEST(KeyedRandom, UniformMoments) {
  std::vector<double> u, pm;
  for (int i = 0; i < kSamples; ++i) {
    const RandomKey key{2024, i / 1000, i % 1000, RandomPurpose::range_noise_second};
    u.push_back(uniform01(key));
    pm.push_back(uniform_pm1(key));
    ASSERT_GE(u.back(), 0.0);
    ASSERT_LT(u.back(), 1.0);
    ASSERT_GE(pm.back(), -1.0);
    ASSERT_LT(pm.back(), 1.0);
  }
  const double n = kSamples;
  const Moments mu = moments(u);
  // U(0,1): mean 1/2, variance 1/12; sampling sd √(1/12/n) and √((1/80 − 1/144)/n).
  EXPECT_NEAR(mu.mean, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(mu.variance, 1.0 / 12.0, 4.0 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n));
  const Moments mpm = moments(pm);
  // U(−1,1): mean 0, variance 1/3; E[x⁴] = 1/5.
  EXPECT_NEAR(mpm.mean, 0.0, 4.0 * std::sqrt(1.0 / 3.0 / n));
  EXPECT_NEAR(mpm.variance, 1.0 / 3.0, 4.0 * std::sqrt((1.0 / 5.0 - 1.0 / 9.0) / n));
}

TEST(KeyedRandom, NormalMomentsAndShape) {
  std::vector<double> z;
  int within_one_sigma = 0;
  for (int i = 0; i < kSamples; ++i) {
    z.push_back(standard_normal(RandomKey{99, 3, i, RandomPurpose::range_noise_first}));
    ASSERT_TRUE(std::isfinite(z.back()));
    if (std::abs(z.back()) < 1.0) ++within_one_sigma;
  }
  const double n = kSamples;
  const Moments m = moments(z);
  EXPECT_NEAR(m.mean, 0.0, 4.0 / std::sqrt(n));
  EXPECT_NEAR(m.variance, 1.0, 4.0 * std::sqrt(2.0 / n));  // Var of s² for N(0,1): 2/n
  const double p = 0.682689492137;                         // P(|z| < 1)
  EXPECT_NEAR(within_one_sigma / n, p, 4.0 * std::sqrt(p * (1 - p) / n));
}

}  // namespace
}  // namespace owsim
