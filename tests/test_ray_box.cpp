// Protects the ray–box slab test (geometry/ray_box.hpp) that the wire pass culls rays with
// (engine/frame_tracer.cpp): pinned cases (inside, a face touched at t_max exactly, a face grazed
// by a parallel ray, an empty box), and blocks of random rays and boxes against the slab clip
// (clip_to_slab, the fog volumes'), an algorithm of its own.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/ray_box.hpp"

namespace owsim {
namespace {

const Eigen::AlignedBox3d kUnit(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());

// One ray through rays_meet_box, in the middle of a block of others that meet nothing.
bool ray_meets_box(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin,
                   const Eigen::Vector3d& dir, double t_max) {
  RayArrays rays;
  for (std::size_t i = 0; i < 9; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      rays.origin[axis][i] = i == 4 ? origin[axis] : 1e6;
      rays.dir[axis][i] = i == 4 ? dir[axis] : 1.0;
    }
    rays.t_max[i] = i == 4 ? t_max : 1.0;
  }
  std::int64_t meets[9];
  rays_meet_box(box, rays, 9, meets);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(meets[i], i == 4 ? meets[4] : 0) << i;
  return meets[4] != 0;
}

TEST(RayBox, PinnedCases) {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  // From inside, any direction and any length.
  EXPECT_TRUE(ray_meets_box(kUnit, {0.5, 0.5, 0.5}, -x, 0.0));
  // Towards the face x = 0 from 1 m away: reached at t = 1 exactly, not before.
  EXPECT_TRUE(ray_meets_box(kUnit, {-1.0, 0.5, 0.5}, x, 1.0));
  EXPECT_FALSE(ray_meets_box(kUnit, {-1.0, 0.5, 0.5}, x, 0.999));
  // Away from the box: never (t ≥ 0 only).
  EXPECT_FALSE(ray_meets_box(kUnit, {-1.0, 0.5, 0.5}, -x, 100.0));
  // Parallel to the face y = 1 and in its plane: the boundary counts; a hair outside does not.
  EXPECT_TRUE(ray_meets_box(kUnit, {-1.0, 1.0, 0.5}, x, 2.0));
  EXPECT_FALSE(ray_meets_box(kUnit, {-1.0, std::nextafter(1.0, 2.0), 0.5}, x, 2.0));
  // Through a corner diagonally.
  EXPECT_TRUE(ray_meets_box(kUnit, {2.0, 2.0, 2.0}, -Eigen::Vector3d::Ones().normalized(), 2.0));
  // An empty box (no conductors) meets nothing.
  EXPECT_FALSE(ray_meets_box(Eigen::AlignedBox3d(), {0.5, 0.5, 0.5}, x, 10.0));
}

// The stretch of t ∈ [0, t_max] inside the box by slabs (clip_to_slab, the fog's clip): an
// algorithm of its own, with divisions and no separating axes. Returns exit − enter: ≥ 0 meets.
double slab_overlap(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin,
                    const Eigen::Vector3d& dir, double t_max) {
  double enter = 0.0, exit = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    clip_to_slab(origin[axis], dir[axis], box.min()[axis], box.max()[axis], enter, exit);
  }
  return exit - enter;
}

TEST(RayBox, RandomRaysAgreeWithSlabs) {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  std::uniform_real_distribution<double> size(0.01, 40.0);
  std::uniform_real_distribution<double> length(0.0, 150.0);
  std::normal_distribution<double> normal;
  int meets = 0, misses = 0;
  RayArrays rays;
  double overlap[RayArrays::kCapacity];
  std::int64_t met[RayArrays::kCapacity];
  for (int block = 0; block < 800; ++block) {
    // One box a block, 250 rays (not a multiple of a vector's lanes).
    const Eigen::Vector3d low(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d high = low + Eigen::Vector3d(size(rng), size(rng), size(rng));
    const Eigen::AlignedBox3d box(low, high);
    constexpr std::size_t kRays = 250;
    for (std::size_t i = 0; i < kRays; ++i) {
      const Eigen::Vector3d origin(coordinate(rng), coordinate(rng), coordinate(rng));
      // Half the rays aimed near the box, so both answers come often.
      Eigen::Vector3d dir(normal(rng), normal(rng), normal(rng));
      if (i % 2 == 0) dir = box.center() - origin + 0.5 * box.sizes().norm() * dir;
      if (i % 7 == 0) dir[i % 3] = 0.0;  // parallel to a face now and then
      dir.normalize();
      const double t_max = length(rng);
      for (int axis = 0; axis < 3; ++axis) {
        rays.origin[axis][i] = origin[axis];
        rays.dir[axis][i] = dir[axis];
      }
      rays.t_max[i] = t_max;
      overlap[i] = slab_overlap(box, origin, dir, t_max);
    }
    rays_meet_box(box, rays, kRays, met);
    for (std::size_t i = 0; i < kRays; ++i) {
      if (std::abs(overlap[i]) < 1e-9) continue;  // within rounding of touching: either answer
      const bool expected = overlap[i] >= 0.0;
      ASSERT_EQ(met[i] != 0, expected)
          << "block " << block << " ray " << i << " overlap " << overlap[i];
      (expected ? meets : misses)++;
    }
  }
  // Both answers well represented.
  EXPECT_GT(meets, 10000);
  EXPECT_GT(misses, 10000);
}

}  // namespace
}  // namespace owsim
