#pragma once
// Navigation records: the import-neutral form of a trajectory (SENSOR-SPEC §5, source ch. 8, 10).
//
// Every trajectory reader (HellSim export, CSV, SBET, ArduPilot log) produces NavRecords:
// time, WGS-84 position and attitude exactly as the file gives them (heading in degrees as
// recorded, true or magnetic, any wrap). to_local turns them into a NavTrack in the scenario's
// local East-North-Up frame (SENSOR-SPEC §4 "Decision (world frame)"), which the trajectory
// (sensor/trajectory.hpp) and the waypoint generator (sensor/waypoint_plan.hpp) share. The
// conversion is GeographicLib's exact LocalCartesian (nanometres); attitudes are copied.
#include <Eigen/Core>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "geometry/rotation.hpp"

namespace owsim {

// One navigation record as read from a file.
struct NavRecord {
  double time_s = 0;  // on the file's clock (each reader says where its zero is)
  Geodetic position;  // WGS-84 latitude, longitude, ellipsoidal height
  Attitude attitude;  // degrees; heading as recorded
};

// A trajectory's records in the scenario's local frame: three parallel arrays of one length.
struct NavTrack {
  std::vector<double> time_s;
  std::vector<Eigen::Vector3d> position_enu_m;
  std::vector<Attitude> attitude;
};

// Records → local ENU (positions only; times and attitudes copied). A position out of range
// throws owsim::Error "navigation record <i>: <problem>" (i 0-based).
[[nodiscard]] NavTrack to_local(const std::vector<NavRecord>& records, const LocalFrame& frame);

}  // namespace owsim
