#pragma once
// Reader for the HellSim ASCII navigation export (SENSOR-SPEC §5, source ch. 8 table 7 and ch. 10).
//
// One record a line, whitespace separated, 15 columns:
//   Pic # | Time-Tag | Heading | Pitch | Roll | X-Vel Y-Vel Z-Vel | N-Vel E-Vel D-Vel | Veloc |
//   Latitude | Long. | Altitude
// angles in degrees, latitude/longitude in degrees, altitude in metres (WGS-84 height). The
// header line (starting "Pic") may appear anywhere and is skipped, as are blank lines and lines
// starting with '#'. Velocities and the picture number are not used.
// Time: Time-Tag counts ticks of tick_s (default 0.0005 s, INTERFACE.md; the source prints only
// the sensor words' 100 µs weight, eq 10.1, and says the navigation counter differs); the first
// record is time 0. The counter is cyclic: a tag smaller than the previous one is a wrap when
// (tag + tag_modulus − previous) ≤ tag_modulus / 2, and an error otherwise; tag_modulus 0
// disables wrapping. Tags must be whole counts and must increase (a repeat is an error).
// Every problem throws owsim::Error "<path>:<line>: <problem>".
#include <cstdint>
#include <string>
#include <vector>

#include "sensor/nav_record.hpp"

namespace owsim {

struct HellSimOptions {
  double tick_s = 0.0005;             // seconds per Time-Tag count
  std::int64_t tag_modulus = 65'536;  // the Time-Tag counter wraps here (16 bits); 0 = never
};

[[nodiscard]] std::vector<NavRecord> read_hellsim(const std::string& path,
                                                  const HellSimOptions& options = {});

}  // namespace owsim
