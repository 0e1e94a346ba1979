// Protects the keyed random generator (geometry/keyed_random): Philox4x32-10 against the
// Random123 known-answer vectors, the independence of keys and purposes, the moments of the
// uniform draws, and the ziggurat standard normal every noise model relies on (scipy's
// Kolmogorov-Smirnov test, tail frequencies, the tail path's shape, determinism).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/keyed_random.hpp"
#include "python_oracle.hpp"

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
  // Includes the normal's extra blocks: they must be no other key's block, nor repeat.
  std::set<PhiloxBlock> seen;
  std::size_t draws = 0;
  for (std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{1} << 32,
                             std::uint64_t{0xdeadbeefcafef00d}}) {
    for (std::int64_t frame : {std::int64_t{0}, std::int64_t{1}, std::int64_t{-1},
                               std::int64_t{1} << 32, std::int64_t{10'000}}) {
      for (std::int64_t pulse : {std::int64_t{0}, std::int64_t{1}, std::int64_t{20'351},
                                 std::int64_t{1} << 32, (std::int64_t{1} << 32) + 1}) {
        for (RandomPurpose purpose : kPurposes) {
          const RandomKey key{seed, frame, pulse, purpose};
          seen.insert(random_block(key));
          for (std::uint32_t index : {0u, 1u, 2u, 1000u})
            seen.insert(normal_extra_block(key, index));
          draws += 5;
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

TEST(KeyedRandom, NormalIsAPureFunctionOfItsKey) {
  const RandomKey key{42, 7, 1234, RandomPurpose::range_noise_first};
  const double z = standard_normal(key);
  EXPECT_EQ(standard_normal(RandomKey{key}), z);
  // Every neighbouring key draws anew.
  for (const RandomKey& other :
       {RandomKey{43, 7, 1234, key.purpose}, RandomKey{41, 7, 1234, key.purpose},
        RandomKey{42, 8, 1234, key.purpose}, RandomKey{42, 6, 1234, key.purpose},
        RandomKey{42, 7, 1235, key.purpose}, RandomKey{42, 7, 1233, key.purpose},
        RandomKey{42, 7, 1234 + (std::int64_t{1} << 32), key.purpose}}) {
    EXPECT_NE(standard_normal(other), z) << other.seed << " " << other.frame << " " << other.pulse;
  }
  for (RandomPurpose purpose : kPurposes) {
    if (purpose != key.purpose) EXPECT_NE(standard_normal({42, 7, 1234, purpose}), z);
  }
}

// Draws N(0, 1) for `count` pulses of one frame.
std::vector<double> normals(const RandomKey& first, int count) {
  std::vector<double> z;
  z.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    z.push_back(standard_normal({first.seed, first.frame, first.pulse + i, first.purpose}));
  }
  return z;
}

// P(|z| > t) for N(0, 1).
double two_sided_tail(double t) { return std::erfc(t / std::numbers::sqrt2); }

// Writes `values` as little-endian float64 to `path` (numpy.fromfile reads them back).
void write_doubles(const std::filesystem::path& path, const std::vector<double>& values) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(values.data()),
             static_cast<std::streamsize>(values.size() * sizeof(double)));
}

TEST(KeyedRandom, NormalPassesScipyGoodnessOfFit) {
  // Two key families: the pulses of one frame, and one pulse over many frames. The
  // Kolmogorov-Smirnov test checks each whole; a chi-square over 100 equiprobable bins of |z|
  // sees the small local errors a wrong wedge test would make.
  constexpr int kPulses = 1'000'000, kFrames = 200'000;
  const std::vector<double> pulses = normals({7, 11, 0, RandomPurpose::range_noise_first}, kPulses);
  std::vector<double> frames;
  for (int frame = 0; frame < kFrames; ++frame) {
    frames.push_back(standard_normal({8, frame, 20'351, RandomPurpose::range_noise_reference}));
  }
  const test::TempDir folder("owsim_keyed_random");
  write_doubles(folder / "pulses.f64", pulses);
  write_doubles(folder / "frames.f64", frames);
  const std::string out = test::run_python(
      "import numpy as np, scipy.stats as st\n"
      "z = np.fromfile('" +
      (folder / "pulses.f64").string() +
      "', dtype='<f8')\n"
      "w = np.fromfile('" +
      (folder / "frames.f64").string() +
      "', dtype='<f8')\n"
      "counts, _ = np.histogram(np.abs(z), st.halfnorm.ppf(np.linspace(0, 1, 101)))\n"
      "print(len(z), len(w), st.kstest(z, 'norm').pvalue, st.kstest(w, 'norm').pvalue,\n"
      "      st.chisquare(counts).pvalue)\n");
  std::istringstream fields(out);
  std::size_t read_pulses = 0, read_frames = 0;
  double ks_pulses = -1.0, ks_frames = -1.0, chi_square = -1.0;
  fields >> read_pulses >> read_frames >> ks_pulses >> ks_frames >> chi_square;
  ASSERT_EQ(read_pulses, pulses.size()) << out;
  ASSERT_EQ(read_frames, frames.size()) << out;
  EXPECT_GT(ks_pulses, 1e-3) << out;
  EXPECT_GT(ks_frames, 1e-3) << out;
  EXPECT_GT(chi_square, 1e-3) << out;
}

// The tail start r of a 256-layer normal ziggurat (Marsaglia & Tsang's construction, as other
// implementations tabulate it): values beyond it come only from the tail path.
constexpr double kTailStart = 3.6541528853610088;

TEST(KeyedRandom, NormalTailFrequencies) {
  constexpr int kDraws = 2'000'000;
  const std::vector<double> z = normals({2024, 5, 0, RandomPurpose::range_noise_second}, kDraws);
  int beyond3 = 0, beyond4 = 0, beyond_r = 0;
  for (const double value : z) {
    beyond3 += std::abs(value) > 3.0;
    beyond4 += std::abs(value) > 4.0;
    beyond_r += std::abs(value) > kTailStart;
  }
  const double n = kDraws;
  for (const auto& [t, count] :
       {std::pair{3.0, beyond3}, std::pair{4.0, beyond4}, std::pair{kTailStart, beyond_r}}) {
    const double p = two_sided_tail(t);  // binomial: mean np, sd √(np(1 − p)); 5σ bound
    EXPECT_NEAR(count, n * p, 5.0 * std::sqrt(n * p * (1.0 - p))) << "P(|z| > " << t << ")";
  }
  // Distinct keys draw distinct values: no value repeats among the two million.
  std::vector<double> sorted = z;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
}

TEST(KeyedRandom, NormalTailPathHasTheTruncatedNormalShape) {
  constexpr int kDraws = 10'000'000;  // ≈ 2,580 draws beyond r
  std::vector<double> tail;
  int positive = 0;
  for (int pulse = 0; pulse < kDraws; ++pulse) {
    const RandomKey key{2025, 6, pulse, RandomPurpose::range_noise_second};
    const double z = standard_normal(key);
    if (std::abs(z) <= kTailStart) continue;
    tail.push_back(std::abs(z));
    positive += z > 0.0;
    // The tail path reads extra blocks: still a pure function of the key.
    ASSERT_EQ(standard_normal(key), z) << pulse;
  }
  const auto k = static_cast<double>(tail.size());
  ASSERT_GT(k, 2000.0);
  EXPECT_NEAR(positive, k / 2.0, 5.0 * std::sqrt(k / 4.0));
  // |z| given |z| > r is the normal truncated at r: mean m = φ(r)/Q(r), variance 1 + r·m − m².
  const double r = kTailStart;
  const double m = std::sqrt(2.0 / std::numbers::pi) * std::exp(-0.5 * r * r) / two_sided_tail(r);
  const double variance = 1.0 + r * m - m * m;
  const Moments tail_moments = moments(tail);
  EXPECT_NEAR(tail_moments.mean, m, 5.0 * std::sqrt(variance / k));  // ±0.5 % of m = 3.897
  // Sample variance: sd σ²·√((κ − 1)/k), κ = 7.19 the kurtosis of that truncated normal (scipy
  // truncnorm(r, ∞)); ±24 % of σ² = 0.0535.
  EXPECT_NEAR(tail_moments.variance, variance, 5.0 * variance * std::sqrt(6.19 / k));
}

// The receiver draws a block of pulses' first-return range noise ahead, on vector lanes: every
// block must be random_block's, for any run length, frame and pulse (the pulse's high bits and a
// negative frame included), and the normal from a given block the key's own.
TEST(KeyedRandom, BlocksOfPulsesAreEachPulsesOwnBlock) {
  for (const std::int64_t frame :
       {std::int64_t{0}, std::int64_t{77}, std::int64_t{-3}, std::int64_t{1} << 40}) {
    for (const std::int64_t first :
         {std::int64_t{0}, std::int64_t{5000}, (std::int64_t{1} << 32) - 100}) {
      for (const std::size_t count :
           {std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{65}, std::size_t{300}}) {
        std::vector<PhiloxBlock> blocks(count);
        random_blocks(0xABCDEF0123456789u, frame, first, RandomPurpose::range_noise_first, blocks);
        for (std::size_t i = 0; i < count; ++i) {
          const RandomKey key{0xABCDEF0123456789u, frame, first + static_cast<std::int64_t>(i),
                              RandomPurpose::range_noise_first};
          ASSERT_EQ(blocks[i], random_block(key)) << frame << " " << first << " " << i;
          ASSERT_EQ(standard_normal(key, blocks[i]), standard_normal(key));
        }
      }
    }
  }
}

// The receiver draws only the pulses that may have a return: the blocks of any list of pulses (out
// of order, repeated, with the high bits, across the lanes' 64) are each its key's own.
TEST(KeyedRandom, BlocksOfListedPulsesAreEachPulsesOwnBlock) {
  std::mt19937_64 random(11);
  for (const std::size_t count :
       {std::size_t{0}, std::size_t{1}, std::size_t{64}, std::size_t{65}, std::size_t{256}}) {
    std::vector<std::int64_t> pulses(count);
    for (std::int64_t& pulse : pulses) {
      pulse = static_cast<std::int64_t>(random() % 3 == 0 ? random() >> 8 : random() % 20352);
    }
    if (count > 2) pulses[2] = pulses[1];
    std::vector<PhiloxBlock> blocks(count);
    random_blocks(0x1234u, -5, pulses, RandomPurpose::echo_detection, blocks);
    for (std::size_t i = 0; i < count; ++i) {
      ASSERT_EQ(blocks[i], random_block({0x1234u, -5, pulses[i], RandomPurpose::echo_detection}))
          << count << " " << i;
    }
  }
  std::vector<PhiloxBlock> one(1);
  EXPECT_THROW(random_blocks(1, 2, std::span<const std::int64_t>(), RandomPurpose::echo_detection,
                             one),
               Error);
}

// The receiver's batch takes the range-noise normals of a run of pulses from their blocks at
// once: each is standard_normal's value where its draw ends in the first block, NaN where the
// ziggurat needs more (its wedges and tail: about 1.5 % of draws).
TEST(KeyedRandom, FirstBlockNormalsAreTheKeysNormals) {
  constexpr int kPulses = 200'000;
  std::vector<PhiloxBlock> blocks(kPulses);
  std::vector<double> normals(kPulses);
  random_blocks(42, 9, 0, RandomPurpose::range_noise_first, blocks);
  first_block_normals(blocks, normals);
  int unknown = 0;
  for (int k = 0; k < kPulses; ++k) {
    const double normal = normals[static_cast<std::size_t>(k)];
    if (std::isnan(normal)) {
      ++unknown;
      continue;
    }
    ASSERT_EQ(normal, standard_normal({42, 9, k, RandomPurpose::range_noise_first})) << k;
  }
  EXPECT_GT(unknown, kPulses / 200);
  EXPECT_LT(unknown, kPulses / 30);
}

}  // namespace
}  // namespace owsim
