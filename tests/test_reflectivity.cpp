// Protects the angular reflectivity curve (SENSOR-SPEC §7, eq 7.12) and the incidence angles it
// is evaluated at (eq 7.11 for wires, the surface normal for poles, trees and ground).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sensor/reflectivity.hpp"

namespace owsim {
namespace {

using Eigen::Vector3d;

TEST(Reflectivity, SpecValues) {
  EXPECT_DOUBLE_EQ(reflectivity_pct(0.0), 40.0);
  EXPECT_NEAR(reflectivity_pct(30.0), 25.03, 0.01);
  EXPECT_NEAR(reflectivity_pct(45.0), 8.07, 0.01);
  EXPECT_EQ(reflectivity_pct(90.0), 0.0);
  EXPECT_NEAR(reflectivity_pct(67.5), 0.5 * reflectivity_pct(45.0), 1e-12);
  // The quartic by hand at 30°: 7.533 − 17.28 − 5.22 + 40.
  EXPECT_NEAR(reflectivity_pct(30.0), 25.033, 1e-9);
}

TEST(Reflectivity, ContinuousAt45AndZeroBeyond90) {
  EXPECT_NEAR(reflectivity_pct(45.0 - 1e-9), reflectivity_pct(45.0 + 1e-9), 1e-6);
  EXPECT_EQ(reflectivity_pct(90.5), 0.0);
  EXPECT_EQ(reflectivity_pct(180.0), 0.0);
  EXPECT_EQ(reflectivity_pct(NAN), 0.0);
}

TEST(Reflectivity, MonotonicDecreasingAndSymmetric) {
  double previous = reflectivity_pct(0.0);
  for (int i = 1; i <= 9000; ++i) {
    const double theta = 0.01 * i;
    const double ref = reflectivity_pct(theta);
    ASSERT_LT(ref, previous) << "θ = " << theta;
    EXPECT_EQ(ref, reflectivity_pct(-theta));
    previous = ref;
  }
}

TEST(Reflectivity, WireIncidenceIsNinetyMinusTheRayAxisAngle) {
  const Vector3d ray(1, 0, 0);
  EXPECT_NEAR(wire_incidence_deg(ray, {0, 1, 0}), 0.0, 1e-12);   // across the wire: normal
  EXPECT_NEAR(wire_incidence_deg(ray, {1, 0, 0}), 90.0, 1e-12);  // along the wire: grazing
  const double a = 30.0 * std::numbers::pi / 180.0;
  const Vector3d axis(std::cos(a), std::sin(a), 0);  // 30° between ray and axis
  EXPECT_NEAR(wire_incidence_deg(ray, axis), 60.0, 1e-12);
  EXPECT_NEAR(wire_incidence_deg(ray, -axis), 60.0, 1e-12);        // the acute angle
  EXPECT_NEAR(wire_incidence_deg(-ray, 5.0 * axis), 60.0, 1e-12);  // any length, any sense
}

TEST(Reflectivity, SurfaceIncidenceIsToTheNormal) {
  const Vector3d down(0, 0, -1);
  EXPECT_NEAR(surface_incidence_deg(down, {0, 0, 1}), 0.0, 1e-12);
  EXPECT_NEAR(surface_incidence_deg(down, {0, 0, -1}), 0.0, 1e-12);  // either normal sense
  const Vector3d slant = Vector3d(1, 0, -1).normalized();
  EXPECT_NEAR(surface_incidence_deg(slant, {0, 0, 1}), 45.0, 1e-12);
  EXPECT_NEAR(surface_incidence_deg({1, 0, 0}, {0, 0, 1}), 90.0, 1e-12);  // grazing
}

}  // namespace
}  // namespace owsim
