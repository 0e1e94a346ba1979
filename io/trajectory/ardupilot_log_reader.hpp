#pragma once
// Reader for the text logs of ArduPilot 2.x (APM 2, 2012) as dumped by its log menu — the real
// flight of /work/shared/data/real (WingFlight1.log). Used to prove trajectory handling on real
// navigation data: heading through north, steep banks, GPS-rate position steps, fix dropouts.
//
// Lines (other message types, e.g. "PM:", are skipped):
//   GPS: time_ms_of_gps_week, fix, sats, lat_deg, lon_deg, sonar, mix_alt_m, gps_alt_m,
//        speed_mps, course_deg
//   ATT: roll_cdeg, pitch_cdeg, yaw_cdeg      (centidegrees; yaw 0–36000 clockwise from north)
// ArduPlane 2.x logs a GPS line, then an ATT line, ~10 times a second; the GPS part updates at
// 4 Hz and repeats in between; fix 0 means no fix.
// Records: one per ATT line, attitude from it (ArduPilot's roll/pitch/yaw signs are owsim's;
// yaw is taken as true heading, as the autopilot applies its declination).
// Times: an ATT line carries none. Consecutive ATT lines that share a GPS time form a group; the
// group's records are spread evenly from its GPS time to the next group's (the last group at the
// previous group's spacing): time = T_g + j · (T_g+1 − T_g) / (records in group g).
// Positions: one GPS fix per distinct GPS time (the first line with fix ≠ 0 at that time), so
// repeated positions do not make a staircase; fix-0 lines are dropped; each record's position is
// the natural cubic spline through the fixes (sensor/cubic_spline.hpp) at its time, which
// bridges the dropouts. Records before the first or after the last fix are dropped.
// Height: gps_alt is the receiver's altitude above mean sea level (the geoid); WGS-84
// ellipsoidal height = gps_alt + geoid_separation_m (≈ +39 m near Oslo for EGM96; default 0,
// i.e. heights relative to the geoid). mix_alt is the barometric altitude relative to the home
// altitude the autopilot fixed at start-up, of no known datum: it is not used.
// Time zero: the first kept record (the GPS time of week there is reported).
// Errors: owsim::Error "<path>:<line>: <problem>" for a malformed GPS or ATT line or a GPS time
// going back; "<path>: <problem>" for fewer than two fixes.
#include <cstddef>
#include <string>
#include <vector>

#include "sensor/nav_record.hpp"

namespace owsim {

struct ArduPilotLogOptions {
  double geoid_separation_m = 0;  // added to gps_alt to give WGS-84 height
};

struct GpsFix {
  double time_s = 0;  // on the records' clock
  Geodetic position;
};

struct ArduPilotLog {
  std::vector<NavRecord> records;  // one per kept ATT line
  std::vector<GpsFix> fixes;       // the de-duplicated fixes the positions pass through
  double gps_time_of_week_at_zero_s = 0;
  std::size_t gps_lines = 0;
  std::size_t att_lines = 0;
  std::size_t no_fix_lines = 0;     // GPS lines with fix 0
  std::size_t dropouts = 0;         // runs of consecutive fix-0 GPS lines
  std::size_t dropped_records = 0;  // ATT lines outside the fixes' time span (or before any GPS)
};

[[nodiscard]] ArduPilotLog read_ardupilot_log(const std::string& path,
                                              const ArduPilotLogOptions& options = {});

}  // namespace owsim
