// Protects round_half_away, round_half_away_in_lanes (below 2⁵²) and round_down
// (geometry/exact_round.hpp): they must equal std::round and std::floor bit for bit on the halves
// and their neighbours, zeros, the 2⁵² edge, inf, NaN and a million random doubles.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "geometry/exact_round.hpp"

namespace owsim {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_same_bits(double got, double want, double x) {
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got)) << x;
  } else {
    EXPECT_EQ(bits(got), bits(want)) << std::hexfloat << x << " gave " << got;
  }
}

void expect_same_as_std(double x) {
  expect_same_bits(round_half_away(x), std::round(x), x);
  expect_same_bits(round_down(x), std::floor(x), x);
  if (std::abs(x) < 0x1p52) expect_same_bits(round_half_away_in_lanes(x), std::round(x), x);
}

TEST(ExactRound, HalvesRoundAwayFromZero) {
  EXPECT_EQ(round_half_away(0.5), 1.0);
  EXPECT_EQ(round_half_away(-0.5), -1.0);
  EXPECT_EQ(round_half_away(2.5), 3.0);
  EXPECT_EQ(round_half_away(-2.5), -3.0);
  EXPECT_EQ(round_half_away(1033.4999), 1033.0);
  EXPECT_TRUE(std::signbit(round_half_away(-0.25)));  // −0, as std::round gives
}

TEST(ExactRound, RoundDownGoesTowardMinusInfinity) {
  EXPECT_EQ(round_down(2.999), 2.0);
  EXPECT_EQ(round_down(-2.001), -3.0);
  EXPECT_EQ(round_down(-3.0), -3.0);
  EXPECT_TRUE(std::signbit(round_down(-0.0)));
}

TEST(ExactRound, EdgesEqualStdRoundAndFloor) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> edges = {0.0,
                               -0.0,
                               inf,
                               -inf,
                               std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::max(),
                               0x1p52,
                               0x1p52 - 0.5,
                               0x1p52 + 1.0,
                               0x1p53 + 2.0,
                               0x1p63,
                               1e300};
  // The halves of the 12-bit counter's and the encoder's ranges, and the largest halves.
  std::vector<double> halves;
  for (double half = 0.5; half < 70000.0; half += 1.0) halves.push_back(half);
  for (double half = 0x1p51 + 0.5; half < 0x1p51 + 100.0; half += 1.0) halves.push_back(half);
  halves.push_back(0x1p52 - 0.5);
  for (const double half : halves) {
    for (const double x : {half, std::nextafter(half, 0.0), std::nextafter(half, inf)}) {
      edges.push_back(x);
    }
  }
  for (const double x : edges) {
    expect_same_as_std(x);
    expect_same_as_std(-x);
  }
}

TEST(ExactRound, RandomDoublesEqualStdRoundAndFloor) {
  std::mt19937_64 random(20261122);
  std::uniform_int_distribution<int> exponent(-60, 70);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  for (int i = 0; i < 1000000; ++i) {
    const double x = std::ldexp(mantissa(random), exponent(random));
    if (bits(round_half_away(x)) != bits(std::round(x)) ||
        (std::abs(x) < 0x1p52 && bits(round_half_away_in_lanes(x)) != bits(std::round(x))) ||
        bits(round_down(x)) != bits(std::floor(x))) {
      ADD_FAILURE() << std::hexfloat << x << ": " << round_half_away(x) << " " << round_down(x);
      return;
    }
  }
}

}  // namespace
}  // namespace owsim
