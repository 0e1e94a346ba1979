// Protects the attitude sign conventions of SENSOR-SPEC §4 (heading 90° points the nose east,
// pitch up raises it, roll right lowers the right wing), the Rz·Ry·Rx order and its inverse.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <random>

#include "geometry/rotation.hpp"

namespace owsim {
namespace {

constexpr double kTol = 1e-12;
double sin_deg(double deg) { return std::sin(deg * std::numbers::pi / 180.0); }
double cos_deg(double deg) { return std::cos(deg * std::numbers::pi / 180.0); }

const Eigen::Vector3d kForward(1, 0, 0), kRight(0, 1, 0), kDown(0, 0, 1);

Eigen::Vector3d body_to_enu(const Attitude& attitude, const Eigen::Vector3d& body) {
  return enu_from_ned(body_to_ned(attitude) * body);
}

void expect_components_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_NEAR(actual.x(), expected.x(), tol) << "actual " << actual.transpose();
  EXPECT_NEAR(actual.y(), expected.y(), tol) << "actual " << actual.transpose();
  EXPECT_NEAR(actual.z(), expected.z(), tol) << "actual " << actual.transpose();
}

TEST(Rotation, AxisRotationsAreRightHandedAndActive) {
  // A positive turn about Z takes X towards Y, about X takes Y towards Z, about Y takes Z to X.
  expect_components_near(rotation_z_deg(90) * Eigen::Vector3d(1, 0, 0), {0, 1, 0}, kTol);
  expect_components_near(rotation_x_deg(90) * Eigen::Vector3d(0, 1, 0), {0, 0, 1}, kTol);
  expect_components_near(rotation_y_deg(90) * Eigen::Vector3d(0, 0, 1), {1, 0, 0}, kTol);
  expect_components_near(rotation_z_deg(30) * Eigen::Vector3d(1, 0, 0), {cos_deg(30), sin_deg(30), 0}, kTol);
  expect_components_near(rotation_y_deg(30) * Eigen::Vector3d(1, 0, 0), {cos_deg(30), 0, -sin_deg(30)}, kTol);
  expect_components_near(rotation_x_deg(30) * Eigen::Vector3d(0, 0, 1), {0, -sin_deg(30), cos_deg(30)}, kTol);
}

TEST(Rotation, HeadingZeroPointsNoseNorthAndNinetyEast) {
  expect_components_near(body_to_enu({0, 0, 0}, kForward), {0, 1, 0}, kTol);
  expect_components_near(body_to_enu({0, 0, 90}, kForward), {1, 0, 0}, kTol);
  expect_components_near(body_to_enu({0, 0, 180}, kForward), {0, -1, 0}, kTol);
  expect_components_near(body_to_enu({0, 0, 270}, kForward), {-1, 0, 0}, kTol);
  // Heading 0: the right wing points east, body down points down.
  expect_components_near(body_to_enu({0, 0, 0}, kRight), {1, 0, 0}, kTol);
  expect_components_near(body_to_enu({0, 0, 0}, kDown), {0, 0, -1}, kTol);
}

TEST(Rotation, PitchUpRaisesTheNose) {
  const Eigen::Vector3d nose = body_to_enu({0, 10, 0}, kForward);
  EXPECT_NEAR(nose.z(), sin_deg(10), kTol);
  EXPECT_NEAR(nose.y(), cos_deg(10), kTol);
  EXPECT_NEAR(nose.x(), 0.0, kTol);
}

TEST(Rotation, RollRightLowersTheRightWing) {
  const Eigen::Vector3d wing = body_to_enu({20, 0, 0}, kRight);
  EXPECT_NEAR(wing.z(), -sin_deg(20), kTol);
  EXPECT_NEAR(wing.x(), cos_deg(20), kTol);
  // The nose stays level and north when only rolling.
  expect_components_near(body_to_enu({20, 0, 0}, kForward), {0, 1, 0}, kTol);
}

TEST(Rotation, AttitudeIsHeadingThenPitchThenRoll) {
  // Non-commuting case: pitch 90° then heading 90° is not heading then pitch.
  const Attitude attitude{30, 40, 50};
  const Eigen::Matrix3d expected = rotation_z_deg(50) * rotation_y_deg(40) * rotation_x_deg(30);
  EXPECT_TRUE(body_to_ned(attitude).isApprox(expected, kTol));
  const Eigen::Matrix3d other_order = rotation_x_deg(30) * rotation_y_deg(40) * rotation_z_deg(50);
  EXPECT_GT((body_to_ned(attitude) - other_order).norm(), 0.1);
  // Roll then heading, worked by hand: roll 90° takes the right wing (0,1,0) to down (0,0,1);
  // heading 90° leaves down alone. Heading applied first would take it to south: (−1,0,0).
  expect_components_near(body_to_ned({90, 0, 90}) * kRight, {0, 0, 1}, kTol);
  // Pitch 90° takes the nose straight up (NED (0,0,−1)); a heading does not move it.
  expect_components_near(body_to_ned({0, 90, 123}) * kForward, {0, 0, -1}, kTol);
  // Pitch 30° with heading 90°: nose east and up.
  expect_components_near(body_to_enu({0, 30, 90}, kForward), {cos_deg(30), 0, sin_deg(30)}, kTol);
}

TEST(Rotation, RandomAttitudesAreProperRotations) {
  std::mt19937_64 rng(20240501);
  std::uniform_real_distribution<double> angle(-360.0, 360.0);
  for (int i = 0; i < 1000; ++i) {
    const Attitude attitude{angle(rng), angle(rng), angle(rng)};
    const Eigen::Matrix3d r = body_to_ned(attitude);
    EXPECT_TRUE((r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-14))
        << attitude.roll_deg << " " << attitude.pitch_deg << " " << attitude.heading_deg;
    EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
  }
}

TEST(Rotation, AttitudeRoundTripsAwayFromGimbalLock) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> roll(-179.9, 179.9), pitch(-89.0, 89.0),
      heading(0.0, 359.9);
  for (int i = 0; i < 2000; ++i) {
    const Attitude in{roll(rng), pitch(rng), heading(rng)};
    const Attitude out = attitude_from_body_to_ned(body_to_ned(in));
    EXPECT_NEAR(out.roll_deg, in.roll_deg, 1e-9) << i;
    EXPECT_NEAR(out.pitch_deg, in.pitch_deg, 1e-9) << i;
    EXPECT_NEAR(out.heading_deg, in.heading_deg, 1e-9) << i;
  }
}

TEST(Rotation, AttitudeRangesAreNormalised) {
  const Attitude west = attitude_from_body_to_ned(body_to_ned({0, 0, -90}));
  EXPECT_NEAR(west.heading_deg, 270.0, 1e-12);
  const Attitude north = attitude_from_body_to_ned(body_to_ned({0, 0, 720}));
  EXPECT_GE(north.heading_deg, 0.0);
  EXPECT_LT(north.heading_deg, 360.0);
  EXPECT_NEAR(std::min(north.heading_deg, 360.0 - north.heading_deg), 0.0, 1e-12);
  // A tiny negative heading wraps to just under 360°, never to 360° itself.
  const Attitude tiny = attitude_from_body_to_ned(body_to_ned({0, 0, -1e-15}));
  EXPECT_LT(tiny.heading_deg, 360.0);
  // Roll beyond 180° comes back in (−180°, 180°]; pitch beyond 90° flips heading and roll.
  EXPECT_NEAR(attitude_from_body_to_ned(body_to_ned({190, 0, 0})).roll_deg, -170.0, 1e-12);
  const Attitude flipped = attitude_from_body_to_ned(body_to_ned({0, 100, 0}));
  EXPECT_NEAR(flipped.pitch_deg, 80.0, 1e-12);
  EXPECT_NEAR(flipped.heading_deg, 180.0, 1e-12);
  EXPECT_NEAR(std::abs(flipped.roll_deg), 180.0, 1e-12);
}

TEST(Rotation, GimbalLockGivesZeroRollAndTheSameRotation) {
  for (const double pitch : {90.0, -90.0}) {
    for (const Attitude in : {Attitude{10, pitch, 40}, Attitude{-35, pitch, 300}}) {
      const Eigen::Matrix3d r = body_to_ned(in);
      const Attitude out = attitude_from_body_to_ned(r);
      EXPECT_EQ(out.roll_deg, 0.0);
      EXPECT_NEAR(out.pitch_deg, pitch, 1e-6);
      EXPECT_GE(out.heading_deg, 0.0);
      EXPECT_LT(out.heading_deg, 360.0);
      EXPECT_TRUE(body_to_ned(out).isApprox(r, 1e-9)) << pitch << " " << in.roll_deg;
    }
  }
  // At +90° pitch only heading − roll is observable: (10, 90, 40) == (0, 90, 30).
  EXPECT_NEAR(attitude_from_body_to_ned(body_to_ned({10, 90, 40})).heading_deg, 30.0, 1e-6);
  // At −90° pitch it is heading + roll: (10, −90, 40) == (0, −90, 50).
  EXPECT_NEAR(attitude_from_body_to_ned(body_to_ned({10, -90, 40})).heading_deg, 50.0, 1e-6);
}

TEST(Rotation, EnuNedSwap) {
  expect_components_near(enu_from_ned({1, 2, 3}), {2, 1, -3}, 0.0);
  expect_components_near(ned_from_enu({2, 1, -3}), {1, 2, 3}, 0.0);
  const Eigen::Matrix3d m = enu_from_ned_matrix();
  expect_components_near(m * Eigen::Vector3d(1, 2, 3), {2, 1, -3}, 0.0);
  EXPECT_EQ(m.determinant(), 1.0);
  EXPECT_TRUE((m * m).isApprox(Eigen::Matrix3d::Identity(), 0.0));
}

}  // namespace
}  // namespace owsim
