// Protects the Savitzky–Golay smoothing of SENSOR-SPEC §5: the source's 5/4 is the identity, the
// 9/3 default reproduces cubics (interior and ends, uniform or not), cuts white noise by the
// published centre-weight factor, and matches scipy.signal.savgol_filter(mode='interp').
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "python_oracle.hpp"
#include "sensor/savitzky_golay.hpp"

namespace owsim {
namespace {

using test::python_list;
using test::run_python;

std::vector<double> random_values(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> values(n);
  for (double& value : values) value = normal(rng);
  return values;
}

double cubic(double t) { return 2.5 - 1.25 * t + 0.4 * t * t - 0.03 * t * t * t; }

TEST(SavitzkyGolay, SourceSpanFiveDegreeFourIsTheIdentity) {
  const std::vector<double> values = random_values(300, 1);
  const std::vector<double> smoothed = savitzky_golay(values, {5, 4});
  ASSERT_EQ(smoothed.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_NEAR(smoothed[i], values[i], 1e-12) << i;
  EXPECT_TRUE(smoothing_is_identity({5, 4}));
  EXPECT_TRUE(smoothing_is_identity({1, 0}));
  EXPECT_TRUE(smoothing_is_identity({7, 9}));
  EXPECT_FALSE(smoothing_is_identity({9, 3}));
  const std::vector<double> window_one = savitzky_golay(values, {1, 0});
  EXPECT_EQ(window_one, values);
}

TEST(SavitzkyGolay, DefaultIsWindowNineDegreeThree) {
  const SmoothingParams defaults;
  EXPECT_EQ(defaults.window, 9);
  EXPECT_EQ(defaults.degree, 3);
}

TEST(SavitzkyGolay, NineThreeReproducesCubicsInteriorAndEnds) {
  std::vector<double> time_s, values;
  for (int i = 0; i < 40; ++i) {
    time_s.push_back(0.1 * i);
    values.push_back(cubic(0.1 * i));
  }
  const std::vector<double> smoothed = savitzky_golay(time_s, values, {9, 3});
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_NEAR(smoothed[i], values[i], 1e-12) << i;
}

TEST(SavitzkyGolay, ReproducesCubicsOnUnevenTimes) {
  // Steps alternating 1/12 s and 1/8 s (3 and 2 attitude records per 4 Hz GPS epoch, as in the
  // real ArduPilot log) and random jitter: a cubic in time is still reproduced exactly.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(0.5, 1.5);
  std::vector<double> time_s{0.0}, values;
  for (int i = 1; i < 60; ++i)
    time_s.push_back(time_s.back() + (i % 2 ? 1.0 / 12 : 0.125) * jitter(rng));
  for (double t : time_s) values.push_back(cubic(t));
  const std::vector<double> smoothed = savitzky_golay(time_s, values, {9, 3});
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_NEAR(smoothed[i], values[i], 1e-11) << i;
}

TEST(SavitzkyGolay, CentreWeightsAreThePublishedTable) {
  // Savitzky & Golay (1964), 9-point quadratic/cubic smoothing: (−21, 14, 39, 54, 59, 54, 39,
  // 14, −21) / 231.
  const std::vector<double> weights = savitzky_golay_centre_weights({9, 3});
  const std::array<double, 9> table = {-21, 14, 39, 54, 59, 54, 39, 14, -21};
  ASSERT_EQ(weights.size(), table.size());
  for (std::size_t k = 0; k < table.size(); ++k) EXPECT_NEAR(weights[k], table[k] / 231.0, 1e-14);
  // 5-point quadratic: (−3, 12, 17, 12, −3) / 35.
  const std::vector<double> five = savitzky_golay_centre_weights({5, 2});
  const std::array<double, 5> five_table = {-3, 12, 17, 12, -3};
  for (std::size_t k = 0; k < five_table.size(); ++k)
    EXPECT_NEAR(five[k], five_table[k] / 35.0, 1e-14);
}

TEST(SavitzkyGolay, WhiteNoiseVarianceDropsBySumOfSquaredWeights) {
  const std::vector<double> weights = savitzky_golay_centre_weights({9, 3});
  double factor = 0.0;
  for (double w : weights) factor += w * w;
  EXPECT_NEAR(factor, 59.0 / 231.0, 1e-14);  // a projection: Σ w² = the centre weight
  const std::vector<double> noise = random_values(200'000, 42);
  const std::vector<double> smoothed = savitzky_golay(noise, {9, 3});
  double in = 0.0, out = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 4; i + 4 < noise.size(); ++i, ++count) {
    in += noise[i] * noise[i];
    out += smoothed[i] * smoothed[i];
  }
  // The ratio's relative standard error is ~√(2/n) ≈ 0.3 %; allow 2 %.
  EXPECT_NEAR(out / in, factor, 0.02 * factor);
}

TEST(SavitzkyGolay, MatchesScipyInterpMode) {
  const std::vector<double> values = random_values(201, 99);
  for (const SmoothingParams params : {SmoothingParams{9, 3}, SmoothingParams{11, 4},
                                       SmoothingParams{7, 2}, SmoothingParams{21, 5}}) {
    std::ostringstream script;
    script << "import numpy as np\nfrom scipy.signal import savgol_filter\n"
           << "x = np.array(" << python_list(values) << ")\n"
           << "y = savgol_filter(x, " << params.window << ", " << params.degree
           << ", mode='interp')\n"
           << "print(' '.join(repr(float(v)) for v in y))\n";
    std::istringstream output(run_python(script.str()));
    const std::vector<double> smoothed = savitzky_golay(values, params);
    for (std::size_t i = 0; i < values.size(); ++i) {
      double expected = 0.0;
      ASSERT_TRUE(output >> expected) << "scipy printed too few values";
      EXPECT_NEAR(smoothed[i], expected, 1e-9)
          << "window " << params.window << " degree " << params.degree << " sample " << i;
    }
  }
}

TEST(SavitzkyGolay, ShortSeriesShrinksTheWindow) {
  // Five samples of a cubic with window 9: the window shrinks to 5 (degree 3) — still exact.
  std::vector<double> values;
  for (int i = 0; i < 5; ++i) values.push_back(cubic(i));
  const std::vector<double> smoothed = savitzky_golay(values, {9, 3});
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_NEAR(smoothed[i], values[i], 1e-12);
  // Six random samples: window 5, degree 3 — a real smoothing, not the identity.
  const std::vector<double> random = random_values(6, 5);
  const std::vector<double> six = savitzky_golay(random, {9, 3});
  double change = 0.0;
  for (std::size_t i = 0; i < random.size(); ++i) change += std::abs(six[i] - random[i]);
  EXPECT_GT(change, 1e-3);
  EXPECT_TRUE(savitzky_golay(std::vector<double>{}, {9, 3}).empty());
}

TEST(SavitzkyGolay, SmoothsSeveralChannelsWithOneTimeBase) {
  std::vector<double> time_s, a, b;
  for (int i = 0; i < 50; ++i) time_s.push_back(0.02 * i);
  a = random_values(50, 11);
  b = random_values(50, 12);
  const std::vector<double> expected_a = savitzky_golay(time_s, a, {9, 3});
  const std::vector<double> expected_b = savitzky_golay(time_s, b, {9, 3});
  std::vector<double>* channels[] = {&a, &b};
  savitzky_golay_in_place(time_s, channels, {9, 3});
  EXPECT_EQ(a, expected_a);
  EXPECT_EQ(b, expected_b);
}

TEST(SavitzkyGolay, RejectsBadParameters) {
  EXPECT_THROW(validate_smoothing({8, 3}, "smoothing"), Error);
  EXPECT_THROW(validate_smoothing({0, 0}, "smoothing"), Error);
  EXPECT_THROW(validate_smoothing({9, -1}, "smoothing"), Error);
  try {
    validate_smoothing({4, 2}, "trajectory.smoothing");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("trajectory.smoothing: smoothing window 4"),
              std::string::npos)
        << error.what();
  }
  const std::vector<double> values = random_values(20, 3);
  EXPECT_THROW((void)savitzky_golay(values, {6, 2}), Error);
}

}  // namespace
}  // namespace owsim
