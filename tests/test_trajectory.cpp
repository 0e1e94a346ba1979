// Protects the trajectory of SENSOR-SPEC §5: validation naming the bad record, heading unwrapped
// through north (no spurious 358° turn, the right sign of the heading rate), magnetic → true,
// exact interpolation of the knots, the local-level → frame rotation, and the held ends.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

const LocalFrame kFrame(Geodetic{48.6881, 10.8447, 450.0});

TrajectoryOptions no_smoothing() {
  TrajectoryOptions options;
  options.smoothing = {1, 0};
  return options;
}

// Level flight north at 40 m/s, one record a second, with the given headings.
NavTrack track_with_headings(const std::vector<double>& headings_deg) {
  NavTrack track;
  for (std::size_t i = 0; i < headings_deg.size(); ++i) {
    track.time_s.push_back(double(i));
    track.position_enu_m.emplace_back(0.0, 40.0 * double(i), 100.0);
    track.attitude.push_back({0.0, 0.0, headings_deg[i]});
  }
  return track;
}

// a − b as an angle in (−180°, 180°]
double angle_difference_deg(double a, double b) { return wrap_180_deg(a - b); }

std::string error_text(const NavTrack& track) {
  try {
    const Trajectory trajectory(track, kFrame);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(Trajectory, HeadingThroughNorthIncreasing) {
  for (const TrajectoryOptions& options : {no_smoothing(), TrajectoryOptions{}}) {
    const Trajectory trajectory(track_with_headings({350, 355, 0, 5, 10}), kFrame, options);
    EXPECT_NEAR(trajectory.pose_at(1.5).attitude.heading_deg, 357.5, 1e-9);  // not 177.5
    EXPECT_NEAR(angle_difference_deg(trajectory.pose_at(2.0).attitude.heading_deg, 0.0), 0.0, 1e-9);
    EXPECT_NEAR(trajectory.pose_at(2.5).attitude.heading_deg, 2.5, 1e-9);
    for (double t = 0.0; t <= 4.0; t += 0.05) {
      const double heading = trajectory.pose_at(t).attitude.heading_deg;
      EXPECT_GE(heading, 0.0);
      EXPECT_LT(heading, 360.0);
      EXPECT_NEAR(trajectory.heading_rate_deg_per_s(t), 5.0, 1e-9) << t;  // 5° per 1 s step
    }
  }
}

TEST(Trajectory, HeadingThroughNorthDecreasing) {
  const Trajectory trajectory(track_with_headings({10, 5, 0, 355, 350}), kFrame, no_smoothing());
  EXPECT_NEAR(trajectory.pose_at(1.5).attitude.heading_deg, 2.5, 1e-9);
  EXPECT_NEAR(trajectory.pose_at(2.5).attitude.heading_deg, 357.5, 1e-9);
  for (double t = 0.0; t <= 4.0; t += 0.05) {
    EXPECT_NEAR(trajectory.heading_rate_deg_per_s(t), -5.0, 1e-9) << t;  // turning left
  }
}

TEST(Trajectory, UnwrapTakesTheShortestTurn) {
  const std::vector<double> unwrapped = unwrap_deg({359, 1, 3, 181, 179, -179, 720.5});
  const std::vector<double> expected = {359, 361, 363, 541, 539, 541, 720.5};
  ASSERT_EQ(unwrapped.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_DOUBLE_EQ(unwrapped[i], expected[i]);
  EXPECT_DOUBLE_EQ(wrap_360_deg(-0.5), 359.5);
  EXPECT_DOUBLE_EQ(wrap_360_deg(720.0), 0.0);
  EXPECT_LT(wrap_360_deg(-1e-17), 360.0);
  EXPECT_DOUBLE_EQ(wrap_180_deg(180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_180_deg(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_180_deg(190.0), -170.0);
}

TEST(Trajectory, SmoothingWorksOnTheUnwrappedHeading) {
  // A noisy heading that wanders across north: smoothing the wrapped values would average 359
  // and 1 to 180. Smoothed, every interpolated heading stays within a few degrees of north.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<double> headings;
  for (int i = 0; i < 200; ++i)
    headings.push_back(wrap_360_deg(2.0 * std::sin(0.05 * i) + noise(rng)));
  const Trajectory trajectory(track_with_headings(headings), kFrame);
  for (double t = 0.0; t <= 199.0; t += 0.1) {
    const double heading = trajectory.pose_at(t).attitude.heading_deg;
    EXPECT_LT(std::min(heading, 360.0 - heading), 5.0) << t;
    EXPECT_LT(std::abs(trajectory.heading_rate_deg_per_s(t)), 5.0) << t;
  }
}

TEST(Trajectory, InterpolatesTheKnotsAndStraightMotion) {
  NavTrack track;
  for (int i = 0; i < 20; ++i) {
    const double t = 0.5 * i;
    track.time_s.push_back(t);
    track.position_enu_m.emplace_back(100.0 + 40.0 * t, -20.0 + 3.0 * t, 300.0 - 1.5 * t);
    track.attitude.push_back({1.0 + 0.2 * t, -2.0 + 0.1 * t, 45.0 + 1.0 * t});
  }
  const Trajectory trajectory(track, kFrame, no_smoothing());
  EXPECT_EQ(trajectory.start_s(), 0.0);
  EXPECT_EQ(trajectory.end_s(), 9.5);
  for (double t = 0.0; t <= 9.5; t += 0.037) {
    const Pose pose = trajectory.pose_at(t);
    EXPECT_EQ(pose.time_s, t);
    EXPECT_NEAR(
        (pose.position_enu_m - Eigen::Vector3d(100.0 + 40.0 * t, -20.0 + 3.0 * t, 300.0 - 1.5 * t))
            .norm(),
        0.0, 1e-9);
    EXPECT_NEAR(pose.attitude.roll_deg, 1.0 + 0.2 * t, 1e-9);
    EXPECT_NEAR(pose.attitude.pitch_deg, -2.0 + 0.1 * t, 1e-9);
    EXPECT_NEAR(pose.attitude.heading_deg, 45.0 + t, 1e-9);
    EXPECT_NEAR(trajectory.heading_rate_deg_per_s(t), 1.0, 1e-9);
  }
  const std::vector<Pose> knots = trajectory.knots();
  ASSERT_EQ(knots.size(), track.time_s.size());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    EXPECT_EQ(knots[i].time_s, track.time_s[i]);
    EXPECT_EQ(knots[i].position_enu_m, track.position_enu_m[i]);
    EXPECT_NEAR(knots[i].attitude.heading_deg, track.attitude[i].heading_deg, 1e-12);
  }
}

TEST(Trajectory, MagneticHeadingBecomesTrue) {
  TrajectoryOptions options = no_smoothing();
  options.heading_magnetic = true;
  options.magnetic_variation_deg = -5.0;  // west variation: true = magnetic − 5°
  const Trajectory trajectory(track_with_headings({2, 2, 2}), kFrame, options);
  EXPECT_NEAR(trajectory.pose_at(0.7).attitude.heading_deg, 357.0, 1e-9);
  options.magnetic_variation_deg = 3.0;
  const Trajectory east(track_with_headings({100, 101, 102}), kFrame, options);
  EXPECT_NEAR(east.pose_at(1.0).attitude.heading_deg, 104.0, 1e-9);
  options.heading_magnetic = false;  // variation ignored for a true heading
  const Trajectory true_heading(track_with_headings({100, 101, 102}), kFrame, options);
  EXPECT_NEAR(true_heading.pose_at(1.0).attitude.heading_deg, 101.0, 1e-9);
}

TEST(Trajectory, FrameRotationFollowsThePosition) {
  // Knots 2.06 km apart (far sparser than any record rate): the quaternion blend between knots
  // errs by ~(Δθ)²/8 with Δθ ≈ 3e-4 rad, i.e. ~2e-8.
  NavTrack track;
  for (int i = 0; i <= 10; ++i) {
    track.time_s.push_back(double(i));
    track.position_enu_m.emplace_back(2000.0 * i, 500.0 * i, 200.0);
    track.attitude.push_back({});
  }
  const Trajectory trajectory(track, kFrame, no_smoothing());
  EXPECT_NEAR((trajectory.pose_at(0.0).frame_from_local_enu -
               kFrame.enu_rotation_at(track.position_enu_m[0]))
                  .norm(),
              0.0, 1e-12);
  for (double t = 0.0; t <= 10.0; t += 0.3) {
    const Pose pose = trajectory.pose_at(t);
    const Eigen::Matrix3d exact = kFrame.enu_rotation_at(pose.position_enu_m);
    EXPECT_NEAR((pose.frame_from_local_enu - exact).norm(), 0.0, 5e-8) << t;
    EXPECT_NEAR((pose.frame_from_local_enu.transpose() * pose.frame_from_local_enu -
                 Eigen::Matrix3d::Identity())
                    .norm(),
                0.0, 1e-14);
  }
  // 20 km east the plumb line has turned ~0.18°: the rotation is not the identity.
  EXPECT_GT((trajectory.pose_at(10.0).frame_from_local_enu - Eigen::Matrix3d::Identity()).norm(),
            1e-3);
  // Knots 200 m apart (200 m/s at 1 Hz): the blend is good to ~1e-10.
  for (double& t : track.time_s) t *= 10.0;
  for (Eigen::Vector3d& p : track.position_enu_m) p *= 0.1;
  const Trajectory dense(track, kFrame, no_smoothing());
  for (double t = 0.0; t <= 100.0; t += 0.7) {
    const Pose pose = dense.pose_at(t);
    EXPECT_NEAR((pose.frame_from_local_enu - kFrame.enu_rotation_at(pose.position_enu_m)).norm(),
                0.0, 1e-9)
        << t;
  }
}

TEST(Trajectory, HoldsTheEndPosesOutsideTheRange) {
  const Trajectory trajectory(track_with_headings({10, 20, 30}), kFrame, no_smoothing());
  EXPECT_EQ(trajectory.pose_at(-3.0).position_enu_m, trajectory.pose_at(0.0).position_enu_m);
  EXPECT_EQ(trajectory.pose_at(9.0).attitude.heading_deg,
            trajectory.pose_at(2.0).attitude.heading_deg);
  EXPECT_EQ(trajectory.heading_rate_deg_per_s(9.0), 0.0);
}

TEST(Trajectory, RollIsUnwrappedAndReportedInHalfOpenRange) {
  NavTrack track = track_with_headings({0, 0, 0, 0});
  track.attitude[0].roll_deg = 170;
  track.attitude[1].roll_deg = 178;
  track.attitude[2].roll_deg = -174;  // rolled on through 180°
  track.attitude[3].roll_deg = -166;
  const Trajectory trajectory(track, kFrame, no_smoothing());
  // 8° a second from 170° through 180° to 194° (−166°).
  EXPECT_NEAR(angle_difference_deg(trajectory.pose_at(1.25).attitude.roll_deg, 180.0), 0.0, 1e-9);
  EXPECT_NEAR(trajectory.pose_at(1.5).attitude.roll_deg, -178.0, 1e-9);
  EXPECT_NEAR(trajectory.pose_at(2.75).attitude.roll_deg, -168.0, 1e-9);
  for (double t = 0.0; t <= 3.0; t += 0.01) {
    const double roll = trajectory.pose_at(t).attitude.roll_deg;
    EXPECT_GT(roll, -180.0);
    EXPECT_LE(roll, 180.0);
  }
}

TEST(Trajectory, NaNIsAnErrorNamingTheRecord) {
  NavTrack track = track_with_headings({0, 1, 2, 3, 4});
  track.attitude[3].roll_deg = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_text(track).find("trajectory record 3: roll is nan"), std::string::npos)
      << error_text(track);
  track = track_with_headings({0, 1, 2, 3, 4});
  track.position_enu_m[2].z() = std::numeric_limits<double>::infinity();
  EXPECT_NE(error_text(track).find("trajectory record 2: up position"), std::string::npos);
  track = track_with_headings({0, 1, 2, 3, 4});
  track.time_s[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_text(track).find("trajectory record 4: time"), std::string::npos);
}

TEST(Trajectory, NonMonotonicTimeIsAnErrorNamingTheRecord) {
  NavTrack track = track_with_headings({0, 1, 2, 3, 4});
  track.time_s[2] = track.time_s[1];  // duplicate
  EXPECT_NE(error_text(track).find("trajectory record 2: time 1 s is not after the previous "
                                   "record's 1 s"),
            std::string::npos)
      << error_text(track);
  track = track_with_headings({0, 1, 2, 3, 4});
  track.time_s[3] = 0.5;  // goes back
  EXPECT_NE(error_text(track).find("trajectory record 3:"), std::string::npos);
  EXPECT_NE(error_text(track_with_headings({7})).find("at least two records"), std::string::npos);
  track = track_with_headings({0, 1, 2});
  track.attitude.pop_back();
  EXPECT_NE(error_text(track).find("differ in length"), std::string::npos);
}

}  // namespace
}  // namespace owsim
