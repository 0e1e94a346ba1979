#pragma once
// A detector's output for `owsim score` (INTERFACE.md "Ground truth and detection evidence"): CSV
// with a header naming `time_s` and either `e_m,n_m,u_m` (the scenario's local frame) or
// `lat_deg,lon_deg,h_m` (WGS-84, ellipsoidal height), optionally `class` and `track`; other
// columns are ignored. A detections file is data from someone else: it is read as text, checked
// cell by cell, and every problem is one owsim::Error "<file>:<line>: <column>: <problem>".
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/geodetic_frame.hpp"

namespace owsim {

struct Detection {
  std::int64_t line = 0;  // in its file
  double time_s = 0.0;
  Eigen::Vector3d enu_m = Eigen::Vector3d::Zero();
  std::string object_class;  // empty when the file has no class column
  std::string track;
};

// The detections of `path`, positions in `frame`'s local ENU.
[[nodiscard]] std::vector<Detection> read_detections_csv(const std::filesystem::path& path,
                                                         const LocalFrame& frame);

}  // namespace owsim
