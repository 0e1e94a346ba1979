#pragma once
// detections.csv (DETECTION-SPEC §5, INTERFACE.md "Obstacle warnings"): one row per warning, in
// frame order and within a frame by track id:
// frame,time_s,track,class,e_m,n_m,u_m,range_m,length_m,width_m,height_m,points
// Positions in the scenario's local ENU frame to the millimetre, times to the nanosecond — the
// cells of points.csv (io/files/csv_cells.hpp), so the bytes do not depend on the host. `owsim
// score` reads the file as it is (evaluation/detections_csv.hpp).
#include <span>
#include <string>
#include <string_view>

#include "detection/obstacle_detector.hpp"

namespace owsim {

inline constexpr std::string_view kDetectionsCsvHeader =
    "frame,time_s,track,class,e_m,n_m,u_m,range_m,length_m,width_m,height_m,points\n";

// Appends the rows of `warnings` to `out`.
void append_detection_rows(std::span<const ObstacleWarning> warnings, std::string& out);

}  // namespace owsim
