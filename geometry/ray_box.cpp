#include "geometry/ray_box.hpp"

#include <algorithm>
#include <utility>

namespace owsim {

void clip_to_slab(double origin, double dir, double low, double high, double& enter, double& exit) {
  if (dir == 0.0) {
    if (origin < low || origin > high) exit = enter - 1.0;  // never inside: empty
    return;
  }
  double t0 = (low - origin) / dir;
  double t1 = (high - origin) / dir;
  if (t0 > t1) std::swap(t0, t1);
  enter = std::max(enter, t0);
  exit = std::min(exit, t1);
}

bool ray_meets_box(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin,
                   const Eigen::Vector3d& dir, double t_max) {
  if (box.isEmpty()) return false;
  // Most misses without a division: both ends of the stretch beyond the same face (the end
  // rounded, which moves it by ~1e-16 of its coordinates).
  const Eigen::Vector3d end = origin + t_max * dir;
  if ((origin.array() < box.min().array() && end.array() < box.min().array()).any() ||
      (origin.array() > box.max().array() && end.array() > box.max().array()).any()) {
    return false;
  }
  double enter = 0.0;
  double exit = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    clip_to_slab(origin[axis], dir[axis], box.min()[axis], box.max()[axis], enter, exit);
  }
  return exit >= enter;
}

}  // namespace owsim
