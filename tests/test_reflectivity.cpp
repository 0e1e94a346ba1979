// Protects the angular reflectivity curve (SENSOR-SPEC §7, eq 7.12) and the incidence angles it
// is evaluated at (eq 7.11 for wires, the surface normal for poles, trees and ground).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

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

// The acute angle replaces the C library's atan2 (the engine evaluates it on vector lanes): it
// must agree with atan2 to 2 ulp over the whole quarter plane, at every reduction boundary, and
// give the exact ends.
TEST(AcuteAngle, WithinTwoUlpOfAtan2) {
  std::mt19937_64 random(46);
  std::uniform_real_distribution<double> angle(0.0, std::numbers::pi / 2);
  std::uniform_real_distribution<double> length(1e-3, 1e3);
  int differing = 0;
  constexpr int kDraws = 200000;
  for (int i = 0; i < kDraws; ++i) {
    const double a = angle(random), r = length(random);
    const double y = r * std::sin(a), x = r * std::cos(a);
    const double expected = std::atan2(y, x) * (180.0 / std::numbers::pi);
    const double got = acute_angle_deg(y, x);
    ASSERT_LE(std::abs(got - expected), 2.0 * std::abs(std::nextafter(expected, 180.0) - expected))
        << "y " << y << " x " << x;
    differing += got != expected;
  }
  EXPECT_LT(differing, kDraws / 3);  // mostly the very same double
  EXPECT_EQ(acute_angle_deg(0.0, 1.0), 0.0);
  EXPECT_EQ(acute_angle_deg(1.0, 0.0), 90.0);
  EXPECT_EQ(acute_angle_deg(0.0, 0.0), 0.0);  // as atan2(0, 0)
  EXPECT_NEAR(acute_angle_deg(1.0, 1.0), 45.0, 1e-13);
  EXPECT_NEAR(acute_angle_deg(1.0, std::sqrt(3.0)), 30.0, 1e-13);
  EXPECT_NEAR(acute_angle_deg(std::sqrt(3.0), 1.0), 60.0, 1e-13);
  // Both sides of the reductions at t = 0.66 and t = tan(3π/8): continuous to rounding.
  for (const double t : {0.66, 2.41421356237309504880}) {
    const double below = acute_angle_deg(std::nextafter(t, 0.0), 1.0);
    const double above = acute_angle_deg(std::nextafter(t, 10.0), 1.0);
    EXPECT_NEAR(above - below, 0.0, 1e-13);
    EXPECT_NEAR(above, std::atan(t) * 180.0 / std::numbers::pi, 1e-13);
  }
  EXPECT_TRUE(std::isnan(acute_angle_deg(NAN, 1.0)));
}

TEST(SurfaceIncidence, ComponentsAndVectorsAgree) {
  const Vector3d ray = Vector3d(0.3, -0.8, -0.52).normalized();
  const Vector3d normal = Vector3d(0.1, 0.2, 0.97).normalized();
  EXPECT_EQ(surface_incidence_deg(ray, normal),
            surface_incidence_deg(ray.x(), ray.y(), ray.z(), normal.x(), normal.y(), normal.z()));
  const double expected = std::acos(std::abs(ray.dot(normal))) * 180.0 / std::numbers::pi;
  EXPECT_NEAR(surface_incidence_deg(ray, normal), expected, 1e-9);
}

}  // namespace
}  // namespace owsim
