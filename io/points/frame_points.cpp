#include "io/points/frame_points.hpp"

#include "geometry/scene.hpp"  // SurfaceClass

namespace owsim {

void frame_points(const FrameView& frame, const LocalFrame& local_frame,
                  std::vector<PointRecord>& out) {
  out.clear();
  for (std::size_t k = 0; k < frame.returns.size(); ++k) {
    const PulseReturns& returns = frame.returns[k];
    const Pulse& pulse = frame.pulses[k];
    const PulseRay& ray = frame.rays[k];
    for (int r = 0; r < returns.count; ++r) {
      const Return& ret = returns.returns[r];
      PointRecord& point = out.emplace_back();
      point.frame = frame.frame;
      point.pulse = pulse.index;
      point.line = pulse.line;
      point.fiber = pulse.fiber;
      point.return_number = r + 1;
      point.number_of_returns = returns.count;
      point.time_s = pulse.time_s;
      point.range_m = ret.range_m;
      point.counter = ret.counter;
      point.enu_m = ray.origin_enu_m + ret.range_m * ray.dir_enu;
      point.geodetic = local_frame.geodetic_from_enu(point.enu_m);
      point.surface = static_cast<SurfaceClass>(ret.surface);
      point.object_index = ret.object_index;
      point.energy_rel = ret.energy_rel;
      point.incidence_deg = ret.incidence_deg;
      point.scan_angle_deg = pulse.beta_deg;
    }
  }
}

}  // namespace owsim
