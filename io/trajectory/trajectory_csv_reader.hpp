#pragma once
// Reader for trajectories as CSV (INTERFACE.md `trajectory.format: csv`).
//
// The first non-blank line is the header; columns are found by name (case-insensitive, any
// order, surrounding spaces and double quotes ignored): time_s, lat_deg, lon_deg, h_m (WGS-84
// ellipsoidal height), roll_deg, pitch_deg, heading_deg. Other columns are ignored, so the
// trajectory.csv owsim writes (time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,
// heading_deg) reads back. Times are taken as written (no shift to 0). Blank lines are skipped.
// Every problem throws owsim::Error "<path>:<line>: <problem>": a missing or repeated column, a
// row with too few cells, a cell that is not a finite number (NaN included), a position out of
// range, no rows at all.
#include <string>
#include <vector>

#include "sensor/nav_record.hpp"

namespace owsim {

[[nodiscard]] std::vector<NavRecord> read_trajectory_csv(const std::string& path);

}  // namespace owsim
