// Protects the fast frame ray build (sensor/frame_rays.hpp): its pulses equal pulse_of_frame's
// field for field, and its rays stay within the stated error of the per-pulse reference (the pose
// at each pulse's own time) on the real recorded flight, the corridor's banked turns and an
// aggressive analytic manoeuvre, with a tilted mount and a lever arm.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/trajectory/ardupilot_log_reader.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/frame_rays.hpp"
#include "sensor/scan_pattern.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

constexpr double kPi = std::numbers::pi;

struct BuiltFrame {
  std::vector<Pulse> pulses;
  std::vector<PulseRay> rays;
  std::vector<std::uint8_t> active;
};

BuiltFrame build_frame(const FrameRayBuilder& builder, const ScanParams& scan,
                       const FrameSweep& sweep, const PoseSource& poses) {
  const auto count = static_cast<std::size_t>(scan.pulses_per_frame());
  BuiltFrame frame{std::vector<Pulse>(count), std::vector<PulseRay>(count),
                   std::vector<std::uint8_t>(count, 7)};
  // In two uneven blocks, as the simulator's parallel_for may split the lines.
  const auto split = static_cast<std::size_t>(5 * scan.fibers_per_line);
  builder.build_lines(sweep, poses, 0, 5, std::span(frame.pulses).first(split),
                      std::span(frame.rays).first(split), std::span(frame.active).first(split));
  builder.build_lines(sweep, poses, 5, scan.lines_per_frame, std::span(frame.pulses).subspan(split),
                      std::span(frame.rays).subspan(split), std::span(frame.active).subspan(split));
  return frame;
}

void expect_same_pulse(const Pulse& got, const Pulse& want) {
  EXPECT_EQ(got.index, want.index);
  EXPECT_EQ(got.line, want.line);
  EXPECT_EQ(got.slot, want.slot);
  EXPECT_EQ(got.fiber, want.fiber);
  EXPECT_EQ(got.reference, want.reference);
  EXPECT_EQ(got.time_s, want.time_s);
  if (!want.reference) EXPECT_EQ(got.alpha_deg, want.alpha_deg);
  EXPECT_EQ(got.mirror_beta_deg, want.mirror_beta_deg);
  EXPECT_EQ(got.beta_deg, want.beta_deg);
  EXPECT_EQ(got.encoder, want.encoder);
  EXPECT_EQ(got.frame_gate, want.frame_gate);
  EXPECT_EQ(got.line_gate, want.line_gate);
  EXPECT_EQ(got.mov_dir, want.mov_dir);
}

TEST(FrameRays, PulsesEqualPulseOfFrameForBothModelsOrdersAndDirections) {
  const FixedPose hover(Pose{});
  for (const SensorModel model : {SensorModel::milows, SensorModel::hellas}) {
    for (const FiberOrder order : {FiberOrder::crosstalk_resorted, FiberOrder::sequential}) {
      ScanParams scan;
      scan.model = model;
      scan.fiber_order = order;
      scan.start_s = 12.5;
      const FrameRayBuilder builder(scan, Mount{});
      // The last two: the flight's pulse index passes 2⁵³ within the frame, and lies beyond 2⁶⁰,
      // where a line's first index is not always a double and the builder times each pulse by
      // pulse_time_s instead of a line's index plus the slot.
      for (const std::int64_t frame_index :
           {std::int64_t{0}, std::int64_t{1}, std::int64_t{7}, std::int64_t{40},
            std::int64_t{442'570'718'098}, std::int64_t{100'000'000'000'000}}) {
        const FrameSweep sweep = frame_sweep(scan, 99, frame_index, frame_index == 7 ? 3.5 : 0.0);
        const BuiltFrame frame = build_frame(builder, scan, sweep, hover);
        int inactive = 0;
        for (int k = 0; k < scan.pulses_per_frame(); ++k) {
          const auto at = static_cast<std::size_t>(k);
          expect_same_pulse(frame.pulses[at], pulse_of_frame(scan, sweep, k));
          EXPECT_EQ(frame.active[at], frame.pulses[at].reference ? 0 : 1);
          inactive += frame.active[at] == 0 ? 1 : 0;
        }
        EXPECT_EQ(inactive, scan.lines_per_frame);  // one reference fiber a line
      }
    }
  }
}

// The largest angle (rad) and origin distance (m) between the fast rays and the reference.
struct RayError {
  double angle_rad = 0;
  double origin_m = 0;
};

RayError ray_error(const ScanParams& scan, const Mount& mount, const PoseSource& poses,
                   const std::vector<std::int64_t>& frames) {
  const FrameRayBuilder builder(scan, mount);
  RayError worst;
  for (const std::int64_t frame_index : frames) {
    const FrameSweep sweep = frame_sweep(scan, 5, frame_index, 0.0);
    const BuiltFrame frame = build_frame(builder, scan, sweep, poses);
    for (std::size_t k = 0; k < frame.pulses.size(); ++k) {
      const Pulse& pulse = frame.pulses[k];
      if (pulse.reference) continue;
      const PulseRay want = pulse_ray(pulse, poses, mount, scan.model);
      const PulseRay& got = frame.rays[k];
      EXPECT_NEAR(got.dir_enu.norm(), 1.0, 1e-15);
      worst.angle_rad = std::max(worst.angle_rad, got.dir_enu.cross(want.dir_enu).norm());
      worst.origin_m = std::max(worst.origin_m, (got.origin_enu_m - want.origin_enu_m).norm());
    }
  }
  return worst;
}

Mount tilted_mount() {
  Mount mount;
  mount.roll_deg = 1.5;
  mount.pitch_deg = -4.0;
  mount.yaw_deg = 2.0;
  mount.lever_arm_m = {2.5, -0.4, 0.8};
  return mount;
}

// Heading turning at 90°/s while the roll swings ±45° at 0.5 Hz (peak 141°/s, 222°/s²) and the
// pitch ±10° at 1 Hz, flying 60 m/s on a circle: far beyond a helicopter's manoeuvres.
class Manoeuvre final : public PoseSource {
 public:
  [[nodiscard]] Pose pose_at(double t) const override {
    Pose pose;
    pose.time_s = t;
    const double heading = 90.0 * t;
    pose.attitude.heading_deg = std::fmod(heading, 360.0);
    pose.attitude.roll_deg = 45.0 * std::sin(kPi * t);
    pose.attitude.pitch_deg = 10.0 * std::sin(2 * kPi * t);
    const double radius = 60.0 / (0.5 * kPi);  // 60 m/s at 90°/s
    pose.position_enu_m = {radius * std::sin(0.5 * kPi * t), radius * std::cos(0.5 * kPi * t),
                           100.0 + 3.0 * std::sin(kPi * t)};
    return pose;
  }
};

TEST(FrameRays, RaysFollowThePerPulsePoseThroughAnAggressiveManoeuvre) {
  ScanParams scan;
  scan.start_s = 0.3;
  const RayError error = ray_error(scan, tilted_mount(), Manoeuvre{}, {0, 1, 2, 3, 4, 5});
  EXPECT_LT(error.angle_rad, 1e-7);
  EXPECT_LT(error.origin_m, 1e-6);
  EXPECT_GT(error.angle_rad, 0.0);  // blended, not recomputed per pulse
}

TEST(FrameRays, RaysFollowThePerPulsePoseThroughTheCorridorsBankedTurns) {
  const Scenario scenario =
      load_scenario(std::filesystem::path(OWSIM_SOURCE_DIR) / "examples/corridor.yaml");
  const LocalFrame local(scenario.origin);
  const Trajectory trajectory = load_trajectory(scenario, local);
  std::vector<std::int64_t> frames;
  for (std::int64_t f = 0; f < 200; f += 9) frames.push_back(f);
  const RayError error = ray_error(scenario.scan, tilted_mount(), trajectory, frames);
  EXPECT_LT(error.angle_rad, 1e-7);
  EXPECT_LT(error.origin_m, 1e-6);
}

TEST(FrameRays, RaysFollowThePerPulsePoseOnTheRealRecordedFlight) {
  const std::filesystem::path log =
      std::filesystem::path(OWSIM_SHARED_DIR) / "data/real/WingFlight1.log";
  if (!std::filesystem::exists(log)) GTEST_SKIP() << log << " is not here";
  const ArduPilotLog flight = read_ardupilot_log(log.string());
  const LocalFrame local(flight.fixes.front().position);
  const Trajectory trajectory(to_local(flight.records, local), local);
  ScanParams scan;
  scan.start_s = trajectory.start_s();
  std::vector<std::int64_t> frames;
  for (std::int64_t f = 0; f < 400; f += 7) frames.push_back(f);  // 0–133 s: the whole flight
  const RayError error = ray_error(scan, tilted_mount(), trajectory, frames);
  EXPECT_LT(error.angle_rad, 1e-7);
  EXPECT_LT(error.origin_m, 1e-6);
}

}  // namespace
}  // namespace owsim
