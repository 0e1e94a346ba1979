#include "geometry/ray_box.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/error.hpp"
#include "geometry/vector_clones.hpp"

// Compiled with -fno-trapping-math (CMakeLists.txt): GCC vectorises rays_meet_box's loop only
// when it may evaluate every comparison of a lane, whatever the others gave.
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

namespace {

// The separating-axis test of segment and box (Ericson, Real-Time Collision Detection §5.3.3): the
// segment's midpoint m and half-length h relative to the box's centre and half-size e; they meet
// unless the box's three axes or the three cross products of h with them separate them. No
// division: a multiply-add pipeline over the block. The answers are int64s so that every array
// of the loop has the lanes of a double: a byte array made GCC take 32 rays an iteration and
// spill most of them to the stack.
OWSIM_VECTOR_CLONES void meet_box(const double (&centre)[3], const double (&half)[3],
                                  const RayArrays& rays, std::size_t n,
                                  std::int64_t* __restrict meets) {
  for (std::size_t i = 0; i < n; ++i) {
    double h[3], m[3];
    bool apart = false;
    for (int axis = 0; axis < 3; ++axis) {
      h[axis] = 0.5 * rays.t_max[i] * rays.dir[axis][i];
      m[axis] = rays.origin[axis][i] + h[axis] - centre[axis];
      apart |= std::abs(m[axis]) > half[axis] + std::abs(h[axis]);
    }
    apart |=
        std::abs(m[1] * h[2] - m[2] * h[1]) > half[1] * std::abs(h[2]) + half[2] * std::abs(h[1]);
    apart |=
        std::abs(m[2] * h[0] - m[0] * h[2]) > half[0] * std::abs(h[2]) + half[2] * std::abs(h[0]);
    apart |=
        std::abs(m[0] * h[1] - m[1] * h[0]) > half[0] * std::abs(h[1]) + half[1] * std::abs(h[0]);
    meets[i] = apart ? 0 : 1;
  }
}

}  // namespace

void rays_meet_box(const Eigen::AlignedBox3d& box, const RayArrays& rays, std::size_t n,
                   std::int64_t* meets) {
  if (n > RayArrays::kCapacity) throw Error("ray box: more rays than a block holds");
  if (box.isEmpty()) {
    std::fill(meets, meets + n, std::int64_t{0});
    return;
  }
  const Eigen::Vector3d mid = box.center(), size = 0.5 * box.sizes();
  const double centre[3] = {mid.x(), mid.y(), mid.z()};
  const double half[3] = {size.x(), size.y(), size.z()};
  meet_box(centre, half, rays, n, meets);
}

}  // namespace owsim
