// Protects the motor encoder ↔ mirror β mapping of SENSOR-SPEC §3: the appendix-A polynomial at
// the spec's checked values, its monotonicity, the inverse and the encoder word round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "python_oracle.hpp"
#include "sensor/motor_encoder.hpp"

namespace owsim {
namespace {

TEST(MotorEncoder, PolynomialMatchesSpecCheckedValues) {
  EXPECT_NEAR(motor_angle_deg(0.0), -115.91, 1e-3);
  EXPECT_NEAR(motor_angle_deg(-18.0), -87.885, 1e-3);
  EXPECT_NEAR(motor_angle_deg(18.0), -145.070, 1e-3);
  EXPECT_NEAR(motor_angle_deg(30.0), -168.661, 1e-3);
}

TEST(MotorEncoder, PolynomialMatchesNumpyPolyval) {
  // Independent evaluation of the same table 4.1 coefficients with numpy.polyval.
  std::istringstream values(test::run_python(
      "import numpy as np\n"
      "c = [4.6809e-17, -7.6174e-15, 2.806e-14, -1.1676e-11, 3.2275e-11, -3.6118e-8, -1.2932e-7,\n"
      "     -0.00013677, -0.0017148, -1.5399, -115.91]\n"
      "print(' '.join(repr(float(np.polyval(c, b))) for b in\n"
      "               [-30, -25.5, -18, -7.25, 0, 3.125, 18, 29.9]))\n"));
  for (double beta : {-30.0, -25.5, -18.0, -7.25, 0.0, 3.125, 18.0, 29.9}) {
    double expected = 0.0;
    ASSERT_TRUE(values >> expected) << "at β = " << beta;
    EXPECT_NEAR(motor_angle_deg(beta), expected, 1e-11) << "at β = " << beta;
  }
}

TEST(MotorEncoder, SlopeIsNegativeAndMatchesFiniteDifferences) {
  double previous = motor_angle_deg(-kMirrorBetaLimitDeg);
  for (int i = -300000; i <= 300000; ++i) {
    const double beta = i * 1e-4;
    const double slope = motor_angle_slope(beta);
    ASSERT_LT(slope, 0.0) << "at β = " << beta;
    if (i % 1000 == 0) {
      const double h = 1e-4;
      const double central = (motor_angle_deg(beta + h) - motor_angle_deg(beta - h)) / (2 * h);
      ASSERT_NEAR(slope, central, 1e-7) << "at β = " << beta;
    }
    if (i > -300000) {
      const double phi = motor_angle_deg(beta);
      ASSERT_LT(phi, previous) << "φ not decreasing at β = " << beta;
      previous = phi;
    }
  }
}

// encoder_word is lround's word without the libm call: the same int16 (the 16-bit word wraps) on
// halves and their neighbours, the int16 edges, values that wrap, huge values, ±0, inf and NaN.
TEST(MotorEncoder, EncoderWordEqualsLroundCastToTheWord) {
  const auto lround_word = [](double counts) {
    return static_cast<EncoderCount>(std::lround(counts));
  };
  std::vector<double> values = {0.0,    -0.0,   0.5,     -0.5,    1.5,     -1.5,  32767.5,
                                -32768.5, 32768.0, -32769.0, 65535.5, 1e9 + 0.5, 0x1p52,
                                0x1p62 + 0x1p10, -0x1p62 - 0x1p11, 0x1p63, -0x1p63, 1e300,
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN()};
  for (double half = -40000.5; half <= 40000.5; half += 997.0) {
    values.push_back(half);
    values.push_back(std::nextafter(half, 0.0));
    values.push_back(std::nextafter(half, half * 2.0));
  }
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> counts(-40000.0, 40000.0);
  for (int i = 0; i < 100000; ++i) values.push_back(counts(random));
  for (const double value : values) {
    if (!(std::abs(value) < 0x1p63)) {
      EXPECT_EQ(encoder_word(value), 0) << value;  // lround: unspecified (glibc: LONG_MIN → 0)
      continue;
    }
    ASSERT_EQ(encoder_word(value), lround_word(value)) << value;
  }
}

TEST(MotorEncoder, EncoderWordOfZeroBeta) {
  EXPECT_EQ(encoder_from_mirror_beta(0.0), -21101);
  EXPECT_EQ(encoder_count(0.0), 0);
  EXPECT_DOUBLE_EQ(kEncoderDegPerCount, 0.0054931640625);
  EXPECT_DOUBLE_EQ(motor_angle_from_encoder_deg(-21101), -21101 * 0.0054931640625);
}

TEST(MotorEncoder, InverseReturnsBetaOnDenseGrid) {
  double worst = 0.0;
  for (int i = -120000; i <= 120000; ++i) {
    const double beta = i * 2.5e-4;
    const double back = mirror_beta_deg_from_motor_angle(motor_angle_deg(beta));
    worst = std::max(worst, std::abs(back - beta));
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(MotorEncoder, InverseClampsOutsideTheMechanicalRange) {
  EXPECT_EQ(mirror_beta_deg_from_motor_angle(motor_angle_deg(-35.0)), -kMirrorBetaLimitDeg);
  EXPECT_EQ(mirror_beta_deg_from_motor_angle(motor_angle_deg(35.0)), kMirrorBetaLimitDeg);
  EXPECT_EQ(mirror_beta_deg_from_motor_angle(0.0), -kMirrorBetaLimitDeg);
  EXPECT_EQ(mirror_beta_deg_from_motor_angle(-400.0), kMirrorBetaLimitDeg);
}

TEST(MotorEncoder, EncoderRoundTripWithinHalfACount) {
  for (int i = -30000; i <= 30000; ++i) {
    const double beta = i * 1e-3;
    const double back = mirror_beta_deg_from_encoder(encoder_from_mirror_beta(beta));
    // Half a count of φ, as β at the local slope (1% margin for the slope's change over it).
    const double half_count_beta = 0.5 * kEncoderDegPerCount / std::abs(motor_angle_slope(beta));
    ASSERT_LE(std::abs(back - beta), 1.01 * half_count_beta) << "at β = " << beta;
  }
}

TEST(MotorEncoder, EveryEncoderWordInRangeRoundTripsExactly) {
  const EncoderCount high = encoder_from_mirror_beta(-kMirrorBetaLimitDeg);
  const EncoderCount low = encoder_from_mirror_beta(kMirrorBetaLimitDeg);
  ASSERT_LT(low, high);
  for (int count = low + 1; count < high; ++count) {
    const auto word = static_cast<EncoderCount>(count);
    ASSERT_EQ(encoder_from_mirror_beta(mirror_beta_deg_from_encoder(word)), word);
  }
}

}  // namespace
}  // namespace owsim
