#pragma once
// The points of one frame: every detected return placed at its simulated range along its pulse's
// ray (INTERFACE.md points.csv: "computed from range_m along the pulse's ray"), with its geodetic
// position and, when the cells carry one, its UTM/UPS grid position (geometry/geodesy_cells.hpp:
// within 10 nm of GeographicLib). object_index is the scene's object index
// (sensor/pulse_candidates.hpp: conductors, cylinders, then the ground). Reuses the caller's
// vector, so a worker allocates nothing per frame once it has grown.
#include <vector>

#include "geometry/geodesy_cells.hpp"
#include "io/points/point_record.hpp"
#include "sensor/frame_view.hpp"

namespace owsim {

// Return r (0-based) of pulse k of `frame` as a point; `cursor` carries the last geodesy cell from
// one call to the next.
// `recorded`: the returns a pulse's word holds (number_of_returns counts no more). `geodetic`
// false: the point is not placed on WGS-84 nor the grid (`geodetic` and `grid_m` keep their
// defaults), for a writer that takes the East-North-Up position only (flight.mcap alone).
[[nodiscard]] PointRecord point_record(const FrameView& frame, std::size_t k, int r,
                                       const GeodesyCells& cells, GeodesyCells::Cursor& cursor,
                                       int recorded = 2, bool geodetic = true);

// Every return of the frame the sensor records (at most `recorded` a pulse: sensor_model.hpp's
// recorded_returns), pulse by pulse and in return order, into `out` (cleared first).
void frame_points(const FrameView& frame, const GeodesyCells& cells, std::vector<PointRecord>& out,
                  int recorded = 2, bool geodetic = true);

}  // namespace owsim
