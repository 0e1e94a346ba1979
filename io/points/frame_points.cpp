#include "io/points/frame_points.hpp"

#include <algorithm>

#include "geometry/scene.hpp"  // SurfaceClass

namespace owsim {

PointRecord point_record(const FrameView& frame, std::size_t k, int r, const GeodesyCells& cells,
                         GeodesyCells::Cursor& cursor, int recorded, bool geodetic) {
  const PulseReturns& returns = frame.returns[k];
  const Pulse& pulse = frame.pulses[k];
  const PulseRay& ray = frame.rays[k];
  const Return& ret = returns.returns[r];
  PointRecord point;
  point.frame = frame.frame;
  point.pulse = pulse.index;
  point.line = pulse.line;
  point.fiber = pulse.fiber;
  point.return_number = r + 1;
  point.number_of_returns = std::min(returns.count, recorded);
  point.time_s = pulse.time_s;
  point.range_m = ret.range_m;
  point.counter = ret.counter;
  point.enu_m = ray.origin_enu_m + ret.range_m * ray.dir_enu;
  if (geodetic) {
    const PlacedPoint placed = cells.place(point.enu_m, cursor);
    point.geodetic = placed.geodetic;
    point.grid_m = placed.grid_m;
  }
  point.surface = static_cast<SurfaceClass>(ret.surface);
  point.object_index = ret.object_index;
  point.energy_rel = ret.energy_rel;
  point.incidence_deg = ret.incidence_deg;
  point.scan_angle_deg = pulse.beta_deg;
  return point;
}

void frame_points(const FrameView& frame, const GeodesyCells& cells, std::vector<PointRecord>& out,
                  int recorded, bool geodetic) {
  out.clear();
  GeodesyCells::Cursor cursor;
  for (std::size_t k = 0; k < frame.returns.size(); ++k) {
    const int count = std::min(frame.returns[k].count, recorded);
    for (int r = 0; r < count; ++r) {
      out.push_back(point_record(frame, k, r, cells, cursor, recorded, geodetic));
    }
  }
}

}  // namespace owsim
