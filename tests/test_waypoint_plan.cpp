// Protects the built-in waypoint generator (SENSOR-SPEC §4 pinned waypoint attitude): straight
// legs at constant speed with heading = track, pitch = flight-path angle, roll 0, time 0 at the
// first waypoint; coordinated fillet turns of radius v²/(g·tan φ) at bank atan(v·ψ̇/g); and the
// errors for corners too tight for their legs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "sensor/trajectory.hpp"
#include "sensor/waypoint_plan.hpp"

namespace owsim {
namespace {

const LocalFrame kPlanFrame(Geodetic{48.6881, 10.8447, 450.0});

TrajectoryOptions plan_without_smoothing() {
  TrajectoryOptions options;
  options.smoothing = {1, 0};
  return options;
}

double heading_difference_deg(double a, double b) { return wrap_180_deg(a - b); }

std::string error_text(const WaypointPlan& plan) {
  try {
    (void)waypoint_track(plan);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(WaypointPlan, TurnRadiusAndBank) {
  // R = v² / (g tan φ): 40 m/s at 30° bank → 1600 / (9.80665 · 0.5773503) = 282.5920 m.
  EXPECT_NEAR(turn_radius_m(40.0, 30.0), 282.5920, 1e-4);
  EXPECT_NEAR(turn_radius_m(60.0, 45.0), 3600.0 / 9.80665, 1e-9);
  // φ = atan(v ψ̇ / g) inverts it: ψ̇ = v / R.
  const double rate_deg_per_s = 40.0 / turn_radius_m(40.0, 30.0) * 180.0 / std::numbers::pi;
  EXPECT_NEAR(coordinated_bank_deg(40.0, rate_deg_per_s), 30.0, 1e-12);
  EXPECT_NEAR(coordinated_bank_deg(40.0, -rate_deg_per_s), -30.0, 1e-12);
  EXPECT_EQ(coordinated_bank_deg(40.0, 0.0), 0.0);
}

TEST(WaypointPlan, StraightLevelLegAtFortyMetresPerSecond) {
  WaypointPlan plan;
  plan.speed_mps = 40;
  plan.points_enu_m = {{-1200, 0, 100}, {400, 0, 100}};  // the INTERFACE.md example
  const NavTrack track = waypoint_track(plan);
  EXPECT_EQ(track.time_s.front(), 0.0);
  EXPECT_NEAR(track.time_s.back(), 1600.0 / 40.0, 1e-12);
  EXPECT_EQ(track.time_s.size(), 40u * 50u + 1u);  // 50 Hz
  for (const TrajectoryOptions& options : {plan_without_smoothing(), TrajectoryOptions{}}) {
    const Trajectory trajectory(track, kPlanFrame, options);
    for (double t = 0.0; t <= 40.0; t += 0.37) {
      const Pose pose = trajectory.pose_at(t);
      EXPECT_NEAR((pose.position_enu_m - Eigen::Vector3d(-1200 + 40 * t, 0, 100)).norm(), 0.0,
                  1e-9);
      EXPECT_NEAR(pose.attitude.heading_deg, 90.0, 1e-9);
      EXPECT_NEAR(pose.attitude.pitch_deg, 0.0, 1e-12);
      EXPECT_NEAR(pose.attitude.roll_deg, 0.0, 1e-12);
      EXPECT_NEAR(trajectory.heading_rate_deg_per_s(t), 0.0, 1e-9);
    }
  }
}

TEST(WaypointPlan, ClimbingLegPitchIsTheFlightPathAngle) {
  WaypointPlan plan;
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 200}};
  const NavTrack track = waypoint_track(plan);
  const double length_m = std::hypot(1000.0, 100.0);
  EXPECT_NEAR(track.time_s.back(), length_m / 40.0, 1e-12);
  const Trajectory trajectory(track, kPlanFrame, plan_without_smoothing());
  const Eigen::Vector3d along = Eigen::Vector3d(0, 1000, 100) / length_m;
  for (double t = 0.0; t <= track.time_s.back(); t += 0.5) {
    const Pose pose = trajectory.pose_at(t);
    EXPECT_NEAR((pose.position_enu_m - (Eigen::Vector3d(0, 0, 100) + 40.0 * t * along)).norm(), 0.0,
                1e-9);
    EXPECT_NEAR(pose.attitude.pitch_deg, std::atan(0.1) * 180.0 / std::numbers::pi,
                1e-9);  // 5.7106°
    EXPECT_NEAR(heading_difference_deg(pose.attitude.heading_deg, 0.0), 0.0, 1e-9);
    EXPECT_NEAR(pose.attitude.roll_deg, 0.0, 1e-12);
  }
}

TEST(WaypointPlan, NinetyDegreeCornerIsACoordinatedFillet) {
  WaypointPlan plan;
  plan.speed_mps = 40;
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 100}, {1000, 1000, 100}};  // north, then east
  const double radius_m = turn_radius_m(40.0, 30.0);
  const double arc_m = std::numbers::pi / 2 * radius_m;
  const double path_m = 2 * (1000.0 - radius_m) + arc_m;  // tangent distance R·tan 45° = R
  const NavTrack track = waypoint_track(plan);
  EXPECT_NEAR(track.time_s.back(), path_m / 40.0, 1e-9);

  const double entry_s = (1000.0 - radius_m) / 40.0;
  const double mid_s = entry_s + 0.5 * arc_m / 40.0;
  for (const TrajectoryOptions& options : {plan_without_smoothing(), TrajectoryOptions{}}) {
    const Trajectory trajectory(track, kPlanFrame, options);
    EXPECT_NEAR(trajectory.pose_at(0.0).attitude.heading_deg, 0.0, 1e-9);
    EXPECT_NEAR(trajectory.pose_at(trajectory.end_s()).attitude.heading_deg, 90.0, 1e-9);
    // Mid-turn: heading 45°, rate v/R, bank atan(v ψ̇ / g) = 30°.
    const Pose mid = trajectory.pose_at(mid_s);
    const double rate = trajectory.heading_rate_deg_per_s(mid_s);
    EXPECT_NEAR(rate, 40.0 / radius_m * 180.0 / std::numbers::pi, 1e-3);
    EXPECT_NEAR(mid.attitude.roll_deg, coordinated_bank_deg(40.0, rate), 0.5);
    EXPECT_NEAR(mid.attitude.roll_deg, 30.0, 0.5);
    EXPECT_NEAR(mid.attitude.heading_deg, 45.0, 1e-3);
    // The fillet misses the corner by R(√2 − 1) = 117.05 m, at mid-turn, along the bisector.
    const Eigen::Vector3d corner(0, 1000, 100);
    const double miss_m = radius_m * (std::sqrt(2.0) - 1.0);
    EXPECT_NEAR((mid.position_enu_m - corner).norm(), miss_m, 1e-3);
    double closest_m = 1e9;
    for (double t = 0.0; t <= trajectory.end_s(); t += 0.01) {
      closest_m = std::min(closest_m, (trajectory.pose_at(t).position_enu_m - corner).norm());
    }
    EXPECT_NEAR(closest_m, miss_m, 1e-3);
    EXPECT_NEAR(trajectory.pose_at(mid_s).position_enu_m.z(), 100.0, 1e-9);
  }
  // On the arc every sample is R from the centre (R, 1000 − R).
  const Eigen::Vector2d centre(radius_m, 1000.0 - radius_m);
  for (std::size_t k = 0; k < track.time_s.size(); ++k) {
    if (track.time_s[k] < entry_s + 0.01 || track.time_s[k] > entry_s + arc_m / 40.0 - 0.01)
      continue;
    EXPECT_NEAR((track.position_enu_m[k].head<2>() - centre).norm(), radius_m, 1e-9);
  }
}

TEST(WaypointPlan, RollRampsInAndOutContinuously) {
  WaypointPlan plan;
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 100}, {-1000, 1000, 100}};  // a left turn
  const NavTrack track = waypoint_track(plan);
  double min_roll = 0.0;
  for (std::size_t k = 1; k < track.time_s.size(); ++k) {
    // 30° over the 1 s ramp at 50 Hz: at most 0.6° a sample.
    EXPECT_LE(std::abs(track.attitude[k].roll_deg - track.attitude[k - 1].roll_deg), 0.6 + 1e-9);
    min_roll = std::min(min_roll, track.attitude[k].roll_deg);
  }
  EXPECT_NEAR(min_roll, -30.0, 1e-9);  // left turn: left wing down
  EXPECT_EQ(track.attitude.front().roll_deg, 0.0);
  EXPECT_EQ(track.attitude.back().roll_deg, 0.0);
  const double entry_s = (1000.0 - turn_radius_m(40.0, 30.0)) / 40.0;
  const Trajectory trajectory(track, kPlanFrame, plan_without_smoothing());
  EXPECT_NEAR(trajectory.pose_at(entry_s).attitude.roll_deg, -15.0, 0.05);  // ramp centred on entry
  EXPECT_NEAR(trajectory.pose_at(entry_s - 0.6).attitude.roll_deg, 0.0, 0.05);
  EXPECT_LT(trajectory.heading_rate_deg_per_s(entry_s + 2.0), -7.0);  // heading decreasing
  EXPECT_NEAR(trajectory.pose_at(trajectory.end_s()).attitude.heading_deg, 270.0, 1e-9);
  // roll_in_s 0: a step.
  plan.roll_in_s = 0.0;
  const NavTrack stepped = waypoint_track(plan);
  double largest_step = 0.0;
  for (std::size_t k = 1; k < stepped.time_s.size(); ++k) {
    largest_step = std::max(
        largest_step, std::abs(stepped.attitude[k].roll_deg - stepped.attitude[k - 1].roll_deg));
  }
  EXPECT_NEAR(largest_step, 30.0, 1e-9);
}

TEST(WaypointPlan, ClimbingThroughATurn) {
  WaypointPlan plan;
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 200}, {1000, 1000, 200}};
  const NavTrack track = waypoint_track(plan);
  // The arc climbs from the tangent point on the first leg (0.1 R below the corner) to the
  // corner's height: path = (1000 − R)·√1.01 + √((πR/2)² + (0.1 R)²) + (1000 − R).
  const double radius_m = turn_radius_m(40.0, 30.0);
  const double path_m = (1000.0 - radius_m) * std::sqrt(1.01) +
                        std::hypot(std::numbers::pi / 2 * radius_m, 0.1 * radius_m) +
                        (1000.0 - radius_m);
  EXPECT_NEAR(track.time_s.back(), path_m / 40.0, 1e-9);
  const Trajectory trajectory(track, kPlanFrame, plan_without_smoothing());
  EXPECT_NEAR(trajectory.pose_at(trajectory.end_s()).position_enu_m.z(), 200.0, 1e-9);
  EXPECT_NEAR(
      (trajectory.pose_at(trajectory.end_s()).position_enu_m - Eigen::Vector3d(1000, 1000, 200))
          .norm(),
      0.0, 1e-9);
  // Speed along the path is 40 m/s everywhere: the chord between samples is 0.8 m, shorter only
  // where it cuts a change of flight-path angle (3.6° at the arc's exit: ≤ 0.025 m/s).
  for (std::size_t k = 1; k < track.time_s.size(); ++k) {
    const double step_m = (track.position_enu_m[k] - track.position_enu_m[k - 1]).norm();
    const double dt = track.time_s[k] - track.time_s[k - 1];
    EXPECT_NEAR(step_m / dt, 40.0, 0.025) << k;
  }
}

TEST(WaypointPlan, TooTightCornerNamesTheWaypoint) {
  WaypointPlan plan;
  plan.points_enu_m = {{0, 0, 100}, {0, 200, 100}, {1000, 200, 100}};  // needs 282.6 m of 200 m
  const std::string text = error_text(plan);
  EXPECT_NE(text.find("trajectory.waypoints.points[1]: the 90° turn at radius 282.592 m"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("too tight"), std::string::npos) << text;
  // Two corners sharing a 400 m leg each need 282.6 m of it: the second is named.
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 100}, {400, 1000, 100}, {400, 0, 100}};
  EXPECT_NE(error_text(plan).find("points[2]"), std::string::npos) << error_text(plan);
  // The last leg too short for the last turn.
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 100}, {100, 1000, 100}};
  EXPECT_NE(error_text(plan).find("points[1]"), std::string::npos) << error_text(plan);
  // A gentler bank widens the turn: 20° needs even more.
  plan.points_enu_m = {{0, 0, 100}, {0, 1000, 100}, {1000, 1000, 100}};
  EXPECT_EQ(error_text(plan), "no error");
  plan.max_bank_deg = 5.0;  // R = 1863 m
  EXPECT_NE(error_text(plan).find("points[1]"), std::string::npos);
}

TEST(WaypointPlan, RejectsBadPlans) {
  WaypointPlan plan;
  plan.points_enu_m = {{0, 0, 100}};
  EXPECT_NE(error_text(plan).find("at least two points"), std::string::npos);
  plan.points_enu_m = {{0, 0, 100}, {0, 0, 300}};
  EXPECT_NE(error_text(plan).find("points[1]: has no horizontal distance"), std::string::npos)
      << error_text(plan);
  plan.points_enu_m = {{0, 0, 100}, {0, 2000, 100}, {0, 0, 100}};
  EXPECT_NE(error_text(plan).find("points[1]: the route reverses"), std::string::npos)
      << error_text(plan);
  plan.points_enu_m = {{0, 0, 100}, {0, 2000, 100}};
  plan.speed_mps = 0;
  EXPECT_NE(error_text(plan).find("speed"), std::string::npos);
  plan.speed_mps = 40;
  plan.max_bank_deg = 90;
  EXPECT_NE(error_text(plan).find("bank"), std::string::npos);
  plan.max_bank_deg = 30;
  plan.sample_hz = -1;
  EXPECT_NE(error_text(plan).find("sample rate"), std::string::npos);
}

TEST(WaypointPlan, StraightThroughACollinearWaypoint) {
  WaypointPlan plan;
  plan.points_enu_m = {{0, 0, 100}, {0, 500, 100}, {0, 1000, 100}};
  const NavTrack track = waypoint_track(plan);
  EXPECT_NEAR(track.time_s.back(), 25.0, 1e-12);
  for (const Attitude& attitude : track.attitude) {
    EXPECT_EQ(attitude.roll_deg, 0.0);
    EXPECT_NEAR(heading_difference_deg(attitude.heading_deg, 0.0), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace owsim
