#pragma once
// The aircraft's pose at any time along a recorded or planned trajectory (SENSOR-SPEC §5,
// source ch. 8 and eq 10.2–10.3): the PoseSource the frame simulator asks for every pulse.
//
// Built once from a NavTrack (local ENU positions, attitudes, times):
//  1. validation — at least two records, every value finite, times strictly increasing; a bad
//     record throws owsim::Error "trajectory record <i>: <problem>" (i 0-based);
//  2. heading (and roll) unwrapped: each step taken as the shortest turn, so 359° → 1° is +2°, not
//     −358° (SENSOR-SPEC §5 decision); a real step of 180° or more between records cannot be told
//     from the other way round;
//  3. magnetic → true: true = magnetic + variation, when the options say the heading is magnetic;
//  4. Savitzky–Golay smoothing of e, n, u, roll, pitch and the unwrapped heading
//     (sensor/savitzky_golay.hpp; window 1 turns it off);
//  5. optional IRS attitude errors (sensor/irs_error.hpp), after smoothing: they model the
//     sensor's pointing error, not noise in the file;
//  6. natural cubic splines of e, n, u, roll, pitch, heading over time (position interpolated in
//     the local Cartesian frame, SENSOR-SPEC §5 decision).
// pose_at returns heading in [0°, 360°), roll in (−180°, 180°], and the local-level → frame
// rotation (LocalFrame::enu_rotation_at), computed at every knot and interpolated (normalised
// quaternion blend: the rotation turns ~0.009° per km, so the blend errs by ~(Δθ)²/8 — 1e-10 rad
// for knots 200 m apart, 1e-8 rad for 2 km).
// pose_at and heading_rate_deg_per_s are const and allocation-free: thread-safe. Outside
// [start_s, end_s] the pose is held at the end (rate 0); the run asks only inside.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "sensor/cubic_spline.hpp"
#include "sensor/irs_error.hpp"
#include "sensor/nav_record.hpp"
#include "sensor/pose_source.hpp"
#include "sensor/savitzky_golay.hpp"

namespace owsim {

struct TrajectoryOptions {
  SmoothingParams smoothing;          // SENSOR-SPEC §5 default window 9, degree 3
  bool heading_magnetic = false;      // the track's heading is magnetic
  double magnetic_variation_deg = 0;  // true = magnetic + variation (east positive)
  bool irs_noise = false;             // add the IRS error model of §5 table 2
  std::uint64_t seed = 0;             // the scenario seed, keys the IRS draws
  IrsErrorModel irs;
};

class Trajectory final : public PoseSource {
 public:
  // frame: the scenario's local frame the track's positions are in (for frame_from_local_enu).
  Trajectory(const NavTrack& track, const LocalFrame& frame, const TrajectoryOptions& options = {});

  [[nodiscard]] Pose pose_at(double time_s) const override;
  // dψ/dt of the heading spline, degrees per second, positive turning right  (SENSOR-SPEC §2)
  [[nodiscard]] double heading_rate_deg_per_s(double time_s) const override;

  [[nodiscard]] double start_s() const { return heading_.knots_x().front(); }
  [[nodiscard]] double end_s() const { return heading_.knots_x().back(); }
  // The processed records the splines pass through (after unwrapping, magnetic → true,
  // smoothing and IRS errors), as poses with heading in [0°, 360°).
  [[nodiscard]] std::vector<Pose> knots() const;

 private:
  [[nodiscard]] Eigen::Matrix3d frame_rotation_in(std::size_t interval, double time_s) const;

  CubicSpline east_, north_, up_, roll_, pitch_, heading_;
  std::vector<Eigen::Quaterniond> frame_from_local_enu_;  // at each knot
};

// Angle in [0°, 360°)
[[nodiscard]] double wrap_360_deg(double angle_deg);
// Angle in (−180°, 180°]
[[nodiscard]] double wrap_180_deg(double angle_deg);
// Unwraps a sequence of angles: each step becomes the equivalent step in [−180°, 180°).
[[nodiscard]] std::vector<double> unwrap_deg(const std::vector<double>& angles_deg);

}  // namespace owsim
