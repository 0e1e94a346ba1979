// Protects the received-energy model (SENSOR-SPEC §7, eq 7.13 and "Pinned per surface"): the
// product of footprint share, angular reflectivity, object reflectivity and transmission, and the
// per-surface candidate rules for wires, poles/trees and ground.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sensor/return_energy.hpp"

namespace owsim {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(ReturnEnergy, ProductOfTheFourFactors) {
  EXPECT_EQ(energy_rel(1.0, 0.0, 1.0, 1.0), 1.0);
  EXPECT_NEAR(energy_rel(0.5, 30.0, 0.4, 0.95), 0.5 * (25.033 / 40.0) * 0.4 * 0.95, 1e-12);
  EXPECT_EQ(energy_rel(0.7, 90.0, 0.4, 0.95), 0.0);
}

// A 20 mm wire crossing the beam centre head-on at 500 m, 1 mrad, A = 0.4, T = 0.95. By hand:
// r_beam = 500·tan(0.5 mrad) = 0.25 m; the strip covers 2·(R²·asin(w/R) + w·√(R² − w²))
// = 9.99733e-3 m² of the disc's 0.19635 m², a share of 0.0509160; energy = 0.0193481.
TEST(ReturnEnergy, TwentyMillimetreWireHeadOnAtFiveHundredMetres) {
  const Atmosphere air;  // T = 0.95
  const auto e = wire_return_energy(0.0, 500.0, 0.01, 0.0, 0.4, BeamParams{}, air);
  EXPECT_TRUE(e.candidate);
  EXPECT_NEAR(e.footprint_fraction, 0.05091599306550352, 1e-13);
  EXPECT_NEAR(e.energy_rel, 0.019348077364891338, 1e-13);
  // The narrow-strip approximation (chord × width, eq 7.9–7.10), 4·r_w / (π·r_beam), is larger
  // by (r_w/r_beam)²/6 = 2.7e-4.
  const double chord_width = 4.0 * 0.01 / (kPi * 0.25);
  EXPECT_NEAR(chord_width / e.footprint_fraction - 1.0, 0.04 * 0.04 / 6.0, 1e-6);
}

TEST(ReturnEnergy, WireCandidateOnlyWhileTheBeamTouchesIt) {
  const Atmosphere air;
  const double r_beam = beam_radius_m(800.0, BeamParams{});  // 0.4 m
  const double reach = 0.01 + r_beam;
  const auto inside = wire_return_energy(reach - 1e-6, 800.0, 0.01, 10.0, 0.4, BeamParams{}, air);
  EXPECT_TRUE(inside.candidate);
  EXPECT_GT(inside.energy_rel, 0.0);
  EXPECT_LT(inside.footprint_fraction, 1e-6);  // a sliver of the disc's rim
  const auto outside = wire_return_energy(reach, 800.0, 0.01, 10.0, 0.4, BeamParams{}, air);
  EXPECT_FALSE(outside.candidate);
  EXPECT_EQ(outside.energy_rel, 0.0);
  // Incidence scales by Ref(θ)/40.
  const auto square = wire_return_energy(0.1, 800.0, 0.01, 0.0, 0.4, BeamParams{}, air);
  const auto slant = wire_return_energy(0.1, 800.0, 0.01, 30.0, 0.4, BeamParams{}, air);
  EXPECT_NEAR(slant.energy_rel / square.energy_rel, 25.033 / 40.0, 1e-9);
}

TEST(ReturnEnergy, WireInHazeUsesTheRangeTransmission) {
  Atmosphere haze;
  haze.visibility_km = 5.0;
  const auto e = wire_return_energy(0.0, 1000.0, 0.01, 0.0, 0.4, BeamParams{}, haze);
  EXPECT_NEAR(e.energy_rel, e.footprint_fraction * 0.4 * 0.60739714, 1e-9);
}

TEST(ReturnEnergy, CylinderWhollyUnderTheBeamIsFullShare) {
  const Atmosphere air;
  // A 0.5 m pole at 200 m: r_beam = 0.1 m, so d + r_beam ≤ 0.25 up to d ≈ 0.15.
  const auto centre = cylinder_return_energy(0.0, 200.0, 0.25, 0.0, 0.3, BeamParams{}, air);
  EXPECT_TRUE(centre.candidate);
  EXPECT_EQ(centre.footprint_fraction, 1.0);
  EXPECT_NEAR(centre.energy_rel, 0.3 * 0.95, 1e-15);
  EXPECT_EQ(
      cylinder_return_energy(0.149, 200.0, 0.25, 0.0, 0.3, BeamParams{}, air).footprint_fraction,
      1.0);
  // Near the edge only part of the beam lands on the pole: the circle–strip share.
  const auto edge = cylinder_return_energy(0.2, 200.0, 0.25, 40.0, 0.3, BeamParams{}, air);
  EXPECT_TRUE(edge.candidate);
  EXPECT_GT(edge.footprint_fraction, 0.5);
  EXPECT_LT(edge.footprint_fraction, 1.0);
  // The central ray must hit: beyond the silhouette there is no cylinder candidate, though the
  // share stays continuous across the edge (half the beam at d = r_cyl when r_beam ≪ r_cyl).
  const auto miss = cylinder_return_energy(0.26, 200.0, 0.25, 0.0, 0.3, BeamParams{}, air);
  EXPECT_FALSE(miss.candidate);
  EXPECT_LT(miss.footprint_fraction, 0.5);
  const auto rim = cylinder_return_energy(0.25, 200.0, 0.25, 0.0, 0.3, BeamParams{}, air);
  EXPECT_TRUE(rim.candidate);
  EXPECT_NEAR(rim.footprint_fraction, 0.5, 1e-6);
  EXPECT_FALSE(cylinder_return_energy(0.36, 200.0, 0.25, 0.0, 0.3, BeamParams{}, air).candidate);
  EXPECT_EQ(cylinder_return_energy(0.36, 200.0, 0.25, 0.0, 0.3, BeamParams{}, air).energy_rel, 0.0);
}

TEST(ReturnEnergy, GroundIsFullShare) {
  const Atmosphere air;
  const auto e = ground_return_energy(300.0, 30.0, 0.2, air);
  EXPECT_TRUE(e.candidate);
  EXPECT_EQ(e.footprint_fraction, 1.0);
  EXPECT_NEAR(e.energy_rel, (25.033 / 40.0) * 0.2 * 0.95, 1e-12);
}

}  // namespace
}  // namespace owsim

namespace owsim {
namespace {

// The wire rule's edge: r_wire + r_beam(R) = 0.01 + 100·tan(0.5 mrad) = 0.0600000042 m at 100 m.
TEST(ReturnEnergy, TheBeamTouchesAWireInsideRWirePlusRBeam) {
  const BeamParams beam{1.0, 0.0};
  EXPECT_TRUE(beam_touches_wire(0.0600000, 100.0, 0.01, beam));
  EXPECT_FALSE(beam_touches_wire(0.0600001, 100.0, 0.01, beam));
  EXPECT_FALSE(beam_touches_wire(0.01 + 100.0 * std::tan(0.5e-3), 100.0, 0.01, beam));  // strict
  // The same rule as wire_return_energy's candidate flag.
  for (const double d : {0.0, 0.03, 0.0599, 0.0601, 1.0}) {
    EXPECT_EQ(beam_touches_wire(d, 100.0, 0.01, beam),
              wire_return_energy(d, 100.0, 0.01, 0.0, 0.4, beam, Atmosphere{}).candidate)
        << d;
  }
}

}  // namespace
}  // namespace owsim
