#include "sensor/nav_record.hpp"

#include <string>

namespace owsim {

NavTrack to_local(const std::vector<NavRecord>& records, const LocalFrame& frame) {
  NavTrack track;
  track.time_s.reserve(records.size());
  track.position_enu_m.reserve(records.size());
  track.attitude.reserve(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    validate_geodetic(records[i].position, "navigation record " + std::to_string(i));
    track.time_s.push_back(records[i].time_s);
    track.position_enu_m.push_back(frame.enu_from_geodetic(records[i].position));
    track.attitude.push_back(records[i].attitude);
  }
  return track;
}

}  // namespace owsim
