// Protects the range counter of SENSOR-SPEC §1: Δ per tick, the noise σ, the timeout range and
// counter_from_range's rounding, clamping and NaN handling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

const RangeCounterParams kDefaults;

TEST(RangeCounter, RangePerCount) {
  EXPECT_NEAR(range_per_count_m(kDefaults), 0.59940, 1e-5);
  EXPECT_DOUBLE_EQ(range_per_count_m(kDefaults), 299'792'500.0 * 4e-9 / (2.0 * 1.0003));
}

TEST(RangeCounter, NoiseSigmaIsDeltaOverRootTwo) {
  EXPECT_DOUBLE_EQ(default_range_noise_sigma_m(kDefaults),
                   range_per_count_m(kDefaults) / std::sqrt(2.0));
  // The spec prints 0.4241; Δ/√2 with Δ = 0.59940 m is 0.42384 m (the 0.4241 comes from the
  // rejected Δ = 0.59975 m of eq 3.2), so the spec's figure holds to 3e-4 only.
  EXPECT_NEAR(default_range_noise_sigma_m(kDefaults), 0.42384, 1e-5);
  EXPECT_NEAR(default_range_noise_sigma_m(kDefaults), 0.4241, 3e-4);
}

TEST(RangeCounter, TimeoutRange) {
  EXPECT_DOUBLE_EQ(timeout_range_m(kDefaults), 2066 * range_per_count_m(kDefaults));
  // 2066 × 0.5994051 = 1238.371 m; the spec's 1238.36 m is 2066 × the rounded 0.5994 m.
  EXPECT_NEAR(timeout_range_m(kDefaults), 1238.371, 1e-3);
  EXPECT_NEAR(timeout_range_m(kDefaults), 1238.36, 0.012);
}

TEST(RangeCounter, CounterRoundsToNearestTick) {
  const double delta = range_per_count_m(kDefaults);
  EXPECT_EQ(counter_from_range(0.0, kDefaults), 0);
  EXPECT_EQ(counter_from_range(10.4 * delta, kDefaults), 10);
  EXPECT_EQ(counter_from_range(10.6 * delta, kDefaults), 11);
  EXPECT_EQ(counter_from_range(100.0, kDefaults), 167);  // 100 / 0.5994052 = 166.83
  EXPECT_EQ(counter_from_range(2065.4 * delta, kDefaults), 2065);
  for (int count = 0; count < 2066; ++count) {
    const auto counter = static_cast<std::uint16_t>(count);
    ASSERT_EQ(counter_from_range(range_from_counter(counter, kDefaults), kDefaults), counter);
  }
}

TEST(RangeCounter, CounterClampsAndHandlesNaN) {
  const double delta = range_per_count_m(kDefaults);
  EXPECT_EQ(counter_from_range(2065.6 * delta, kDefaults), 2066);
  EXPECT_EQ(counter_from_range(5000.0, kDefaults), 2066);
  EXPECT_EQ(counter_from_range(std::numeric_limits<double>::infinity(), kDefaults), 2066);
  EXPECT_EQ(counter_from_range(std::numeric_limits<double>::quiet_NaN(), kDefaults), 2066);
  EXPECT_EQ(counter_from_range(-3.0, kDefaults), 0);
  EXPECT_EQ(counter_from_range(-std::numeric_limits<double>::infinity(), kDefaults), 0);
}

TEST(RangeCounter, RangeFromCounter) {
  EXPECT_DOUBLE_EQ(range_from_counter(0, kDefaults), 0.0);
  EXPECT_NEAR(range_from_counter(10, kDefaults), 5.994052, 1e-6);
  EXPECT_DOUBLE_EQ(range_from_counter(2066, kDefaults), timeout_range_m(kDefaults));
}

TEST(RangeCounter, ParametersAreHonoured) {
  RangeCounterParams p;
  p.timer_period_s = 8e-9;
  p.timeout_counts = 1000;
  EXPECT_DOUBLE_EQ(range_per_count_m(p), 2.0 * range_per_count_m(kDefaults));
  EXPECT_EQ(counter_from_range(1e6, p), 1000);
  EXPECT_DOUBLE_EQ(timeout_range_m(p), 1000 * range_per_count_m(p));
}

// RangeCounter multiplies by 1/Δ; every counter must still be round(range/Δ)'s, above all where
// the quotient lies on or next to a half count (where a product one ulp off would round the
// other way without the fallback to the division).
void expect_same_counters(const RangeCounterParams& p) {
  const RangeCounter counters(p);
  const double delta = range_per_count_m(p);
  const auto check = [&](double range) {
    ASSERT_EQ(counters.counter(range), counter_from_range(range, p)) << "range " << range;
  };
  int near_half = 0;
  for (int count = -3; count < p.timeout_counts + 3; ++count) {
    const double half = (count + 0.5) * delta;
    double range = half;
    for (int step = 0; step < 4; ++step) range = std::nextafter(range, -1e300);
    for (int step = 0; step < 9; ++step, range = std::nextafter(range, 1e300)) {
      check(range);
      if (std::abs(range / delta - count) == 0.5) ++near_half;
    }
  }
  EXPECT_GT(near_half, 100);  // the sweep did meet quotients exactly on a half count
  std::mt19937_64 engine(20261122);
  std::uniform_real_distribution<double> uniform(-10.0, 1.1 * timeout_range_m(p));
  for (int i = 0; i < 200'000; ++i) check(uniform(engine));
  for (const double special : {0.0, -0.0, 1e300, -1e300, std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::quiet_NaN(), 0x1p52 * delta}) {
    check(special);
  }
}

TEST(RangeCounter, ReciprocalCounterIsTheDivisionsBitForBit) {
  expect_same_counters(kDefaults);
  RangeCounterParams p;
  p.timer_period_s = 3e-9;  // a Δ whose reciprocal rounds differently
  p.refractive_index_air = 1.00029;
  p.timeout_counts = 4095;
  expect_same_counters(p);
}

}  // namespace
}  // namespace owsim
