#include "geometry/fog_volume.hpp"

#include "geometry/ray_box.hpp"

namespace owsim {

std::optional<PathInterval> path_interval(const FogVolume& volume, const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& dir, double t_max_m) {
  double enter = 0.0;
  double exit = t_max_m;
  switch (volume.shape) {
    case FogShape::sky:
      break;
    case FogShape::layer:
      clip_to_slab(origin.z(), dir.z(), volume.base_m, volume.top_m, enter, exit);
      break;
    case FogShape::box:
      for (int axis = 0; axis < 3; ++axis) {
        clip_to_slab(origin[axis], dir[axis], volume.box.min()[axis], volume.box.max()[axis], enter,
                     exit);
      }
      break;
  }
  if (!(exit > enter)) return std::nullopt;
  return PathInterval{enter, exit};
}

}  // namespace owsim
