// Protects the beam radius r_beam(R) = r_exit + R·tan(divergence/2) (SENSOR-SPEC §7).
#include <gtest/gtest.h>

#include <cmath>

#include "sensor/beam.hpp"

namespace owsim {
namespace {

TEST(Beam, OneMilliradianIsHalfAMetreAtOneKilometre) {
  EXPECT_NEAR(beam_radius_m(1000.0, BeamParams{}), 0.5, 1e-6);
  EXPECT_DOUBLE_EQ(beam_radius_m(1000.0, BeamParams{}), 1000.0 * std::tan(0.0005));
}

TEST(Beam, DefaultsAreTheSpecs) {
  const BeamParams beam;
  EXPECT_EQ(beam.divergence_mrad, 1.0);
  EXPECT_EQ(beam.exit_radius_m, 0.0);
  EXPECT_EQ(beam_radius_m(0.0, beam), 0.0);
}

TEST(Beam, ExitRadiusAddsAndRadiusGrowsLinearly) {
  const BeamParams beam{.divergence_mrad = 2.0, .exit_radius_m = 0.03};
  EXPECT_DOUBLE_EQ(beam_radius_m(0.0, beam), 0.03);
  EXPECT_NEAR(beam_radius_m(500.0, beam), 0.03 + 500.0 * std::tan(0.001), 1e-15);
  const double slope = beam_radius_m(300.0, beam) - beam_radius_m(200.0, beam);
  EXPECT_NEAR(beam_radius_m(1200.0, beam) - beam_radius_m(1100.0, beam), slope, 1e-12);
}

}  // namespace
}  // namespace owsim
