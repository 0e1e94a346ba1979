// Protects where every fiber points (SENSOR-SPEC §4 "Pinned conventions"): ARC → SRC → model →
// mount → body → NED → ENU, for MilOWS and HELLAS, and the per-pose precomputation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "geometry/rotation.hpp"
#include "sensor/mounting.hpp"

namespace owsim {
namespace {

constexpr double kTol = 1e-14;
double sin_deg(double deg) { return std::sin(deg * std::numbers::pi / 180.0); }
double cos_deg(double deg) { return std::cos(deg * std::numbers::pi / 180.0); }

void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << " expected " << expected.transpose();
}

TEST(Mounting, ArcUnitRayIsEq91To93) {
  const Eigen::Vector3d abc = arc_unit_ray(-21.0, 12.0);
  EXPECT_NEAR(abc.x(), sin_deg(-21), kTol);
  EXPECT_NEAR(abc.y(), cos_deg(-21) * sin_deg(12), kTol);
  EXPECT_NEAR(abc.z(), cos_deg(-21) * cos_deg(12), kTol);
  EXPECT_NEAR(abc.norm(), 1.0, kTol);
  expect_near(arc_unit_ray(0, 0), {0, 0, 1}, kTol);  // c is the propagation axis
  expect_near(src_from_arc({1, 2, 3}), {3, 1, 2}, 0.0);
}

TEST(Mounting, ModelRotations) {
  EXPECT_TRUE(model_rotation(SensorModel::hellas).isIdentity(0.0));
  EXPECT_TRUE(model_rotation(SensorModel::milows).isApprox(rotation_x_deg(-90), 1e-15));
  // MilOWS: v = (c, b, −a).
  expect_near(model_rotation(SensorModel::milows) * src_from_arc({0.1, 0.2, 0.3}), {0.3, 0.2, -0.1},
              0.0);
}

TEST(Mounting, MilowsFiberDirectionsInTheBody) {
  const Mount none;
  expect_near(ray_direction_body(SensorModel::milows, none, 0, 0), {1, 0, 0}, kTol);
  // Fiber 1 (α = −21°) looks down (body z > 0), fiber 65 (α = +21°) up.
  const Eigen::Vector3d fiber1 = ray_direction_body(SensorModel::milows, none, -21, 0);
  EXPECT_NEAR(fiber1.z(), sin_deg(21), kTol);
  EXPECT_NEAR(fiber1.x(), cos_deg(21), kTol);
  EXPECT_NEAR(ray_direction_body(SensorModel::milows, none, 21, 0).z(), -sin_deg(21), kTol);
  // β positive looks right: the mirror sweep is horizontal ("looks into a turn").
  const Eigen::Vector3d right = ray_direction_body(SensorModel::milows, none, 0, 18);
  EXPECT_NEAR(right.y(), sin_deg(18), kTol);
  EXPECT_NEAR(right.z(), 0.0, kTol);
  expect_near(ray_direction_body(SensorModel::milows, none, 10, -15),
              {cos_deg(10) * cos_deg(-15), cos_deg(10) * sin_deg(-15), -sin_deg(10)}, kTol);
}

TEST(Mounting, HellasFiberDirectionsInTheBody) {
  // HELLAS: PRC = SRC, v = (c, a, b): α positive looks right, β positive looks down.
  const Mount none;
  expect_near(ray_direction_body(SensorModel::hellas, none, 0, 0), {1, 0, 0}, kTol);
  const Eigen::Vector3d alpha_right = ray_direction_body(SensorModel::hellas, none, 21, 0);
  EXPECT_NEAR(alpha_right.y(), sin_deg(21), kTol);
  EXPECT_NEAR(alpha_right.z(), 0.0, kTol);
  const Eigen::Vector3d beta_down = ray_direction_body(SensorModel::hellas, none, 0, 18);
  EXPECT_NEAR(beta_down.z(), sin_deg(18), kTol);
  EXPECT_NEAR(beta_down.y(), 0.0, kTol);
}

TEST(Mounting, MountPitchMinusFourLooksFourDegreesDown) {
  Mount mount;
  mount.pitch_deg = -4.0;
  const Eigen::Vector3d boresight = ray_direction_body(SensorModel::milows, mount, 0, 0);
  expect_near(boresight, {cos_deg(4), 0, sin_deg(4)}, kTol);
  EXPECT_NEAR(std::asin(boresight.z()) * 180.0 / std::numbers::pi, 4.0, 1e-12);
  // Mount yaw 10° turns the boresight right, mount roll moves the β sweep off the horizon.
  EXPECT_NEAR(ray_direction_body(SensorModel::milows, Mount{0, 0, 10, {}}, 0, 0).y(), sin_deg(10),
              kTol);
  EXPECT_NEAR(ray_direction_body(SensorModel::milows, Mount{30, 0, 0, {}}, 0, 18).z(),
              sin_deg(18) * sin_deg(30), kTol);
  EXPECT_TRUE(mount_rotation(Mount{1, 2, 3, {}})
                  .isApprox(rotation_z_deg(3) * rotation_y_deg(2) * rotation_x_deg(1), 1e-15));
}

TEST(Mounting, LeverArmTurnsWithTheAircraft) {
  Pose pose;
  pose.position_enu_m = {100, 200, 300};
  pose.attitude.heading_deg = 90;
  Mount mount;
  mount.lever_arm_m = {2, 0, 0};  // 2 m forward of the body origin
  const SensorPlacement placement = sensor_placement(pose, mount, SensorModel::milows);
  expect_near(placement.origin_enu_m, {102, 200, 300}, 1e-12);
  // Heading 90°: boresight east; a lever arm 1 m below the body origin stays below it.
  expect_near(ray_direction_enu(placement, 0, 0), {1, 0, 0}, kTol);
  mount.lever_arm_m = {0, 0, 1};
  expect_near(sensor_placement(pose, mount, SensorModel::milows).origin_enu_m, {100, 200, 299},
              1e-12);
  // Pitch up 30°: a forward lever arm rises.
  pose.attitude = {0, 30, 0};
  mount.lever_arm_m = {2, 0, 0};
  expect_near(sensor_placement(pose, mount, SensorModel::hellas).origin_enu_m,
              {100, 200 + 2 * cos_deg(30), 300 + 2 * sin_deg(30)}, 1e-12);
}

TEST(Mounting, PlacementEqualsTheStepByStepChain) {
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> angle(-180.0, 180.0), small(-30.0, 30.0),
      metres(-5000.0, 5000.0), arm(-3.0, 3.0);
  for (int i = 0; i < 500; ++i) {
    const SensorModel model = i % 2 == 0 ? SensorModel::milows : SensorModel::hellas;
    Pose pose;
    pose.position_enu_m = {metres(rng), metres(rng), metres(rng)};
    pose.attitude = {angle(rng), small(rng), angle(rng) + 180.0};
    const Mount mount{small(rng), small(rng), small(rng), {arm(rng), arm(rng), arm(rng)}};
    const double alpha = small(rng) * 0.7, beta = small(rng);

    // The chain spelled out one frame at a time.
    const Eigen::Vector3d abc{sin_deg(alpha), cos_deg(alpha) * sin_deg(beta),
                              cos_deg(alpha) * cos_deg(beta)};
    const Eigen::Vector3d v_src{abc.z(), abc.x(), abc.y()};
    const Eigen::Vector3d v_model =
        model == SensorModel::milows ? Eigen::Vector3d(v_src.x(), v_src.z(), -v_src.y()) : v_src;
    const Eigen::Vector3d v_body =
        rotation_z_deg(mount.yaw_deg) *
        (rotation_y_deg(mount.pitch_deg) * (rotation_x_deg(mount.roll_deg) * v_model));
    const auto to_ned = [&](const Eigen::Vector3d& body) -> Eigen::Vector3d {
      return rotation_z_deg(pose.attitude.heading_deg) *
             (rotation_y_deg(pose.attitude.pitch_deg) *
              (rotation_x_deg(pose.attitude.roll_deg) * body));
    };
    const Eigen::Vector3d v_ned = to_ned(v_body);
    const Eigen::Vector3d v_enu{v_ned.y(), v_ned.x(), -v_ned.z()};
    const Eigen::Vector3d arm_ned = to_ned(mount.lever_arm_m);
    const Eigen::Vector3d origin =
        pose.position_enu_m + Eigen::Vector3d(arm_ned.y(), arm_ned.x(), -arm_ned.z());

    const SensorPlacement placement = sensor_placement(pose, mount, model);
    expect_near(ray_direction_enu(placement, alpha, beta), v_enu, 1e-12);
    expect_near(placement.origin_enu_m, origin, 1e-12);
    expect_near(
        enu_from_ned(body_to_ned(pose.attitude) * ray_direction_body(model, mount, alpha, beta)),
        v_enu, 1e-12);
    EXPECT_NEAR(ray_direction_enu(placement, alpha, beta).norm(), 1.0, 1e-14);
  }
}

TEST(Mounting, LocalLevelRotationTurnsRaysAndLeverArm) {
  // Away from the origin the pose's local-level axes are rotated into the frame's axes.
  Pose pose;
  pose.attitude.heading_deg = 90;
  pose.frame_from_local_enu = rotation_y_deg(0.2);  // local up leans 0.2° to frame east
  Mount mount;
  mount.lever_arm_m = {0, 0, 1};
  const SensorPlacement placement = sensor_placement(pose, mount, SensorModel::milows);
  expect_near(ray_direction_enu(placement, 0, 0), rotation_y_deg(0.2) * Eigen::Vector3d(1, 0, 0),
              kTol);
  expect_near(placement.origin_enu_m, rotation_y_deg(0.2) * Eigen::Vector3d(0, 0, -1), kTol);
}

}  // namespace
}  // namespace owsim
