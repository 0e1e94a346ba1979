#pragma once
// Reader for Applanix SBET trajectories (Smoothed Best Estimate of Trajectory, POSPac output;
// INTERFACE.md `trajectory.format: sbet`).
//
// No header; records of 17 little-endian IEEE doubles (136 bytes): time (s, GPS seconds of week
// as written, not shifted), latitude (rad), longitude (rad), altitude (m, WGS-84 ellipsoidal),
// x/y/z velocity (m/s, wander frame; unused), roll (rad), pitch (rad), platform heading (rad),
// wander angle (rad), x/y/z body acceleration, x/y/z body angular rate (unused).
// Attitude: roll right-wing-down and pitch nose-up positive, as owsim's. True heading =
// platform heading − wander angle (Applanix: the platform heading is measured in the
// wander-azimuth frame, whose x axis lies the wander angle from true north; exporters with no
// wander frame write 0), wrapped to [0°, 360°).
// Errors (owsim::Error): an unreadable file, a size that is not a whole number of records
// ("<path>: truncated record at byte N", N = where the partial record starts), a value that is
// not finite or a position out of range ("<path>: record <i> at byte <N>: <problem>"), no records.
#include <string>
#include <vector>

#include "sensor/nav_record.hpp"

namespace owsim {

inline constexpr std::size_t kSbetRecordBytes = 17 * 8;

[[nodiscard]] std::vector<NavRecord> read_sbet(const std::string& path);

}  // namespace owsim
