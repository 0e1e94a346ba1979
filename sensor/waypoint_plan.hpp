#pragma once
// The built-in trajectory generator: a planned flight through waypoints (INTERFACE.md
// `trajectory.waypoints`, SENSOR-SPEC §4 "Pinned waypoint attitude").
//
// Straight legs between waypoints at constant speed (along the 3-D path): heading = track,
// pitch = flight-path angle, roll 0; time 0 at the first waypoint. At every inner waypoint a
// coordinated turn: a horizontal circular arc of radius R = v² / (g · tan φmax) tangent to both
// legs (a fillet: it starts and ends R · tan(|Δψ|/2) before and after the corner), flown at
// bank φ = atan(v · ψ̇ / g) (= φmax on a level turn), the height changing linearly along the arc
// between the two tangent points. The path misses the corner by R · (1/cos(Δψ/2) − 1).
// Roll: a linear ramp of roll_in_s centred on each tangent point (shortened to the arc's duration
// when the arc is shorter), so roll is continuous; 0 makes it a step. The position stays on the
// fillet during the ramp (the ramp idealises a real roll-in, which would widen the turn slightly).
// Sampled uniformly at ≤ 1/sample_hz (the last sample lands on the last waypoint).
// Errors (owsim::Error, "trajectory.waypoints…: problem"): fewer than two points, a leg without
// horizontal extent, a corner whose fillet does not fit the legs (names the waypoint), a reversal.
#include <Eigen/Core>
#include <vector>

#include "sensor/nav_record.hpp"

namespace owsim {

inline constexpr double kStandardGravityMps2 = 9.80665;

struct WaypointPlan {
  double speed_mps = 40;
  std::vector<Eigen::Vector3d> points_enu_m;  // local ENU metres
  double max_bank_deg = 30;                   // the bank of every turn, (0°, 90°)
  double sample_hz = 50;                      // records per second, at least
  double roll_in_s = 1.0;                     // roll ramp at each turn entry and exit; 0 = step
};

// Radius of a level coordinated turn, R = v² / (g · tan φ)  (SENSOR-SPEC §4 pinned waypoints)
[[nodiscard]] double turn_radius_m(double speed_mps, double bank_deg);
// Bank of a coordinated turn, φ = atan(v · ψ̇ / g), ψ̇ in degrees per second  (SENSOR-SPEC §4)
[[nodiscard]] double coordinated_bank_deg(double speed_mps, double heading_rate_deg_per_s);

// The plan flown and sampled: a NavTrack starting at time 0 at the first waypoint.
[[nodiscard]] NavTrack waypoint_track(const WaypointPlan& plan);

}  // namespace owsim
