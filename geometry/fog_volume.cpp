#include "geometry/fog_volume.hpp"

#include <algorithm>
#include <cmath>

namespace owsim {
namespace {

// Narrows [enter, exit] to where origin + t·dir has its coordinate between low and high.
void clip_slab(double origin, double dir, double low, double high, double& enter, double& exit) {
  if (dir == 0.0) {
    if (origin < low || origin > high) exit = -1.0;  // never inside: empty
    return;
  }
  double t0 = (low - origin) / dir;
  double t1 = (high - origin) / dir;
  if (t0 > t1) std::swap(t0, t1);
  enter = std::max(enter, t0);
  exit = std::min(exit, t1);
}

}  // namespace

std::optional<PathInterval> path_interval(const FogVolume& volume, const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& dir, double t_max_m) {
  double enter = 0.0;
  double exit = t_max_m;
  switch (volume.shape) {
    case FogShape::sky:
      break;
    case FogShape::layer:
      clip_slab(origin.z(), dir.z(), volume.base_m, volume.top_m, enter, exit);
      break;
    case FogShape::box:
      for (int axis = 0; axis < 3; ++axis) {
        clip_slab(origin[axis], dir[axis], volume.box.min()[axis], volume.box.max()[axis], enter,
                  exit);
      }
      break;
  }
  if (!(exit > enter)) return std::nullopt;
  return PathInterval{enter, exit};
}

}  // namespace owsim
