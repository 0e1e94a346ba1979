// Protects trajectory handling on real navigation data (/work/shared/data/real/WingFlight1.log,
// an ArduPilot fixed-wing flight): the reader's record, fix and dropout counts; a Trajectory that
// builds; a yaw that crosses north many times unwrapped into whole circles with no impossible
// step; finite poses; no ±360°/dt heading-rate spike; and positions through every GPS fix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "io/trajectory/ardupilot_log_reader.hpp"
#include "owsim/simulation.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

const std::string kLog = std::string(OWSIM_SHARED_DIR) + "/data/real/WingFlight1.log";

class RealFlight : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { log_ = new ArduPilotLog(read_ardupilot_log(kLog)); }
  static void TearDownTestSuite() {
    delete log_;
    log_ = nullptr;
  }
  static ArduPilotLog* log_;
};
ArduPilotLog* RealFlight::log_ = nullptr;

std::vector<double> record_headings(const ArduPilotLog& log) {
  std::vector<double> headings;
  for (const NavRecord& record : log.records) headings.push_back(record.attitude.heading_deg);
  return headings;
}

TEST_F(RealFlight, ReaderCountsRecordsFixesAndDropouts) {
  // Counted independently (Python over the file): 1398 GPS/ATT pairs; 107 GPS lines without a
  // fix in 4 runs (lines 159–181, 309–317, 530–578, 626–754); 515 distinct GPS times with a fix.
  // The last GPS time (66349.5 s) has two ATT lines; the second is after the last fix: 1397 kept.
  EXPECT_EQ(log_->gps_lines, 1398u);
  EXPECT_EQ(log_->att_lines, 1398u);
  EXPECT_EQ(log_->no_fix_lines, 107u);
  EXPECT_EQ(log_->dropouts, 4u);
  EXPECT_EQ(log_->fixes.size(), 515u);
  EXPECT_EQ(log_->records.size(), 1397u);
  EXPECT_EQ(log_->dropped_records, 1u);
  EXPECT_DOUBLE_EQ(log_->gps_time_of_week_at_zero_s, 66210.25);
  EXPECT_EQ(log_->records.front().time_s, 0.0);
  EXPECT_NEAR(log_->records.back().time_s, 66349.5 - 66210.25, 1e-9);  // 139.25 s
  // First record: ATT -24, -24, 1172 with GPS 59.9631350, 10.7263600, gps_alt 208.82.
  EXPECT_NEAR(log_->records.front().attitude.roll_deg, -0.24, 1e-12);
  EXPECT_NEAR(log_->records.front().attitude.heading_deg, 11.72, 1e-12);
  EXPECT_NEAR(log_->records.front().position.lat_deg, 59.9631350, 1e-12);
  EXPECT_NEAR(log_->records.front().position.h_m, 208.82, 1e-9);
  // Times increase strictly, ~10 records a second.
  for (std::size_t i = 1; i < log_->records.size(); ++i) {
    EXPECT_GT(log_->records[i].time_s, log_->records[i - 1].time_s) << i;
  }
}

TEST_F(RealFlight, YawCrossesNorthAndUnwrapsIntoWholeCircles) {
  const std::vector<double> headings = record_headings(*log_);
  int crossings = 0;
  for (std::size_t i = 1; i < headings.size(); ++i) {
    if (std::abs(headings[i] - headings[i - 1]) > 180.0) ++crossings;
  }
  EXPECT_GE(crossings, 10);  // 13 in this flight
  const std::vector<double> unwrapped = unwrap_deg(headings);
  // Three left-hand circles: −1079.02° net over the 1397 kept records (11.72° → 12.70°).
  EXPECT_NEAR(unwrapped.back() - unwrapped.front(), -1079.02, 0.005);
  EXPECT_LT(unwrapped.back() - unwrapped.front(), -2.0 * 360.0);
  // The largest yaw step between records is 12.7° (~150°/s at 10 Hz): nothing near the 180° an
  // unwrap error would leave.
  double largest_step = 0.0;
  for (std::size_t i = 1; i < unwrapped.size(); ++i) {
    largest_step = std::max(largest_step, std::abs(unwrapped[i] - unwrapped[i - 1]));
  }
  EXPECT_LT(largest_step, 20.0);
  EXPECT_GT(largest_step, 5.0);  // the airframe does turn hard
}

TEST_F(RealFlight, TrajectoryGivesFinitePosesWithoutSpuriousTurns) {
  const LocalFrame frame(log_->fixes.front().position);
  const NavTrack track = to_local(log_->records, frame);
  const Trajectory trajectory(track, frame);  // default smoothing 9/3
  EXPECT_EQ(trajectory.start_s(), 0.0);
  EXPECT_NEAR(trajectory.end_s(), 139.25, 1e-9);
  double largest_rate = 0.0, integrated_turn = 0.0;
  const double dt = 0.01;
  for (double t = trajectory.start_s(); t < trajectory.end_s(); t += dt) {
    const Pose pose = trajectory.pose_at(t);
    ASSERT_TRUE(pose.position_enu_m.allFinite()) << t;
    ASSERT_TRUE(std::isfinite(pose.attitude.roll_deg) && std::isfinite(pose.attitude.pitch_deg));
    ASSERT_GE(pose.attitude.heading_deg, 0.0) << t;
    ASSERT_LT(pose.attitude.heading_deg, 360.0) << t;
    ASSERT_TRUE(pose.frame_from_local_enu.allFinite());
    const double rate = trajectory.heading_rate_deg_per_s(t);
    largest_rate = std::max(largest_rate, std::abs(rate));
    integrated_turn += rate * dt;
  }
  // A wrap taken the wrong way would show as ~360°/0.1 s = 3600°/s; the smoothed flight peaks
  // near 100°/s.
  EXPECT_LT(largest_rate, 250.0);
  EXPECT_GT(largest_rate, 30.0);
  // The integral of the heading rate is the unwrapped turn: three circles left, no extra ±360°.
  const std::vector<double> unwrapped = unwrap_deg(record_headings(*log_));
  EXPECT_NEAR(integrated_turn, unwrapped.back() - unwrapped.front(), 5.0);
}

TEST_F(RealFlight, PositionsPassThroughEveryGpsFix) {
  const LocalFrame frame(log_->fixes.front().position);
  const Trajectory trajectory(to_local(log_->records, frame), frame);
  double worst_m = 0.0;
  for (const GpsFix& fix : log_->fixes) {
    if (fix.time_s < trajectory.start_s() || fix.time_s > trajectory.end_s()) continue;
    const Eigen::Vector3d expected = frame.enu_from_geodetic(fix.position);
    worst_m = std::max(worst_m, (trajectory.pose_at(fix.time_s).position_enu_m - expected).norm());
  }
  EXPECT_LT(worst_m, 3.0);
  // Across the dropouts (the longest: no fix from 66241.25 to 66247.5 s, during a U-turn) the
  // spline bridges the gap without a jump: no step above 1 m between 10 ms samples (100 m/s).
  // The fixes themselves jump at up to 76 m/s where the GPS glitches (66329.75 → 66330.0 s:
  // 19 m south in 0.25 s), so the bound is not the airframe's 22 m/s.
  double largest_step_m = 0.0;
  for (double t = trajectory.start_s(); t + 0.01 <= trajectory.end_s(); t += 0.01) {
    largest_step_m = std::max(largest_step_m, (trajectory.pose_at(t + 0.01).position_enu_m -
                                               trajectory.pose_at(t).position_enu_m)
                                                  .norm());
  }
  EXPECT_LT(largest_step_m, 1.0);
  EXPECT_GT(largest_step_m, 0.1);  // the aircraft does move
}

// A scenario flies the log as its trajectory (format: ardupilot): the Simulation's trajectory is
// the reader's (smoothing off: window 1), its clock from the log's first record.
TEST_F(RealFlight, AScenarioFliesTheLogAsItsTrajectory) {
  const Geodetic first = log_->fixes.front().position;
  const std::string yaml =
      "origin: {lat: " + std::to_string(first.lat_deg) + ", lon: " + std::to_string(first.lon_deg) +
      ", h: " + std::to_string(first.h_m) +
      "}\ntrajectory: {file: WingFlight1.log, format: ardupilot, start_s: 20, duration_s: 2, "
      "smoothing: {window: 1, degree: 0}}\n"
      "scene: {terrain: none}\n";
  const Simulation simulation = Simulation::from_yaml(
      yaml, std::filesystem::path(kLog).parent_path() / "real.yaml");  // anchors the log's name
  EXPECT_EQ(simulation.frame_count(), 6);
  const LocalFrame frame(simulation.scenario().origin);
  TrajectoryOptions unsmoothed;
  unsmoothed.smoothing = SmoothingParams{1, 0};
  const Trajectory expected(to_local(log_->records, frame), frame, unsmoothed);
  for (const double t : {20.0, 21.0, 22.0}) {
    EXPECT_LT((simulation.setup().trajectory.pose_at(t).position_enu_m -
               expected.pose_at(t).position_enu_m)
                  .norm(),
              1e-6);
  }
  EXPECT_NO_THROW((void)simulation.simulate_frame(0));
}

}  // namespace
}  // namespace owsim
