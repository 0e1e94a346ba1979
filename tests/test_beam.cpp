// Protects the beam radius r_beam(R) = r_exit + R·tan(divergence/2) (SENSOR-SPEC §7).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <thread>

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

// The tangent is kept for the last divergence a thread asked for: divergences taken in turn, on
// two threads, each get their own radius bit for bit — 0, −0 and NaN included.
TEST(Beam, EachDivergenceGetsItsOwnTangentInAnyOrder) {
  const double divergences[] = {1.0, 2.5, 1.0, 0.0, -0.0, 0.3, std::nan(""), 0.3, 1.0};
  const auto check = [&] {
    for (int pass = 0; pass < 3; ++pass) {
      for (const double divergence : divergences) {
        const BeamParams beam{.divergence_mrad = divergence, .exit_radius_m = 0.01};
        const double expected = 0.01 + 750.0 * std::tan(0.5e-3 * divergence);
        const double radius = beam_radius_m(750.0, beam);
        if (std::isnan(expected)) {
          EXPECT_TRUE(std::isnan(radius)) << divergence;
        } else {
          EXPECT_EQ(std::bit_cast<std::uint64_t>(radius), std::bit_cast<std::uint64_t>(expected))
              << divergence;
        }
      }
    }
  };
  std::thread other(check);
  check();
  other.join();
}

}  // namespace
}  // namespace owsim
