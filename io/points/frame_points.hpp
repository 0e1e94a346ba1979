#pragma once
// The points of one frame: every detected return placed at its simulated range along its pulse's
// ray (INTERFACE.md points.csv: "computed from range_m along the pulse's ray"), with its geodetic
// position. object_index is the scene's object index (sensor/pulse_candidates.hpp: conductors,
// cylinders, then the ground). Reuses the caller's vector, so a worker allocates nothing per frame
// once it has grown.
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "io/points/point_record.hpp"
#include "sensor/frame_view.hpp"

namespace owsim {

// Return r (0-based) of pulse k of `frame` as a point.
[[nodiscard]] PointRecord point_record(const FrameView& frame, std::size_t k, int r,
                                       const LocalFrame& local_frame);

// Every return of the frame, pulse by pulse and in return order, into `out` (cleared first).
void frame_points(const FrameView& frame, const LocalFrame& local_frame,
                  std::vector<PointRecord>& out);

}  // namespace owsim
