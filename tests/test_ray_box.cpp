// Protects the ray–box slab test (geometry/ray_box.hpp) that the wire pass culls rays with
// (engine/frame_tracer.cpp) and the fog boxes clip with: pinned cases (inside, a face touched at
// t_max exactly, a face grazed by a parallel ray, an empty box), and random rays and boxes
// against an independent separating-axis test of segment and box.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/ray_box.hpp"

namespace owsim {
namespace {

const Eigen::AlignedBox3d kUnit(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());

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

// How far apart the segment p0 + t·d, t ∈ [0, t_max], and the box lie along the axis that
// separates them best of Ericson's 6 (the box's 3 and their cross products with d); ≤ 0: they
// meet. An algorithm of its own: no slabs.
double separation(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p0,
                  const Eigen::Vector3d& d, double t_max) {
  const Eigen::Vector3d half_box = 0.5 * box.sizes();
  const Eigen::Vector3d half_segment = 0.5 * t_max * d;
  const Eigen::Vector3d offset = p0 + half_segment - box.center();
  double worst = -INFINITY;
  for (int axis = 0; axis < 3; ++axis) {
    worst = std::max(worst, std::abs(offset[axis]) - half_box[axis] - std::abs(half_segment[axis]));
  }
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d normal = half_segment.cross(Eigen::Vector3d::Unit(axis));
    const double length = normal.norm();
    if (length < 1e-12) continue;
    const double reach = half_box.dot(normal.cwiseAbs());
    worst = std::max(worst, (std::abs(offset.dot(normal)) - reach) / length);
  }
  return worst;
}

TEST(RayBox, RandomRaysAgreeWithSeparatingAxes) {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  std::uniform_real_distribution<double> size(0.01, 40.0);
  std::uniform_real_distribution<double> length(0.0, 150.0);
  std::normal_distribution<double> normal;
  int meets = 0, misses = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const Eigen::Vector3d low(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d high = low + Eigen::Vector3d(size(rng), size(rng), size(rng));
    const Eigen::AlignedBox3d box(low, high);
    const Eigen::Vector3d origin(coordinate(rng), coordinate(rng), coordinate(rng));
    // Half the rays aimed near the box, so both answers come often.
    Eigen::Vector3d dir(normal(rng), normal(rng), normal(rng));
    if (trial % 2 == 0) dir = box.center() - origin + 0.5 * box.sizes().norm() * dir;
    if (trial % 7 == 0) dir[trial % 3] = 0.0;  // parallel to a face now and then
    dir.normalize();
    const double t_max = length(rng);
    const double apart = separation(box, origin, dir, t_max);
    if (std::abs(apart) < 1e-9) continue;  // within rounding of touching: either answer
    const bool expected = apart < 0.0;
    ASSERT_EQ(ray_meets_box(box, origin, dir, t_max), expected)
        << "trial " << trial << " separation " << apart;
    (expected ? meets : misses)++;
  }
  // Both answers well represented.
  EXPECT_GT(meets, 10000);
  EXPECT_GT(misses, 10000);
}

}  // namespace
}  // namespace owsim
