#pragma once
// A detector's output for `owsim score` (INTERFACE.md "Ground truth and detection evidence"): CSV
// with a header naming `time_s` and either `e_m,n_m,u_m` (the scenario's local frame) or
// `lat_deg,lon_deg,h_m` (WGS-84, ellipsoidal height), optionally `class` and `track`; other
// columns are ignored. A detections file is data from someone else: it is read as text, checked
// cell by cell against docs/evidence.md's bounds — finite numbers, times within the flight (±
// kDetectionTimeMarginS), latitudes within ±90°, longitudes within ±360°, positions within
// kMaxDetectionDistanceM of the scenario origin, class and track UTF-8 of at most 256 bytes — and
// every problem is one owsim::Error "<file>:<line>: <column>: <problem>".
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "geometry/geodetic_frame.hpp"

namespace owsim {

inline constexpr double kMaxDetectionDistanceM = 1'000'000.0;  // 1,000 km
inline constexpr double kDetectionTimeMarginS = 60.0;  // a detector's latency, with room to spare

struct Detection {
  std::int64_t line = 0;  // in its file
  double time_s = 0.0;
  Eigen::Vector3d enu_m = Eigen::Vector3d::Zero();
  std::string object_class;  // empty when the file has no class column
  std::string track;
};

// The flight the detections were made on: in `frame`'s local ENU, its first pulse at `start_s`
// and its last at `end_s` (trajectory time, as points.csv and truth.csv give it).
struct DetectionFlight {
  const LocalFrame& frame;
  double start_s = 0.0;
  double end_s = 0.0;
};

// Calls each(detection) for the detections of `path` (at most 256 MiB) in file order, positions in
// the flight's local ENU; none is kept. Throws owsim::Error at the first bad cell.
void read_detections_csv(const std::filesystem::path& path, const DetectionFlight& flight,
                         const std::function<void(const Detection&)>& each);

}  // namespace owsim
