// Protects the ray–wire closest approach (SENSOR-SPEC §7, eq 7.1–7.7): the true minimum over
// t ≥ 0 and s ∈ [0, 1], including parallel lines and clamping, against brute-force sampling.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "geometry/ray_segment.hpp"

namespace owsim {
namespace {

using Eigen::Vector3d;

double distance_at(const Vector3d& o, const Vector3d& u, const Vector3d& p0, const Vector3d& p1,
                   double t, double s) {
  return (o + t * u - (p0 + s * (p1 - p0))).norm();
}

TEST(RaySegment, PerpendicularSkewLines) {
  const auto a = closest_approach({0, 0, 0}, {1, 0, 0}, {5, -1, 2}, {5, 1, 2});
  EXPECT_NEAR(a.ray_t, 5.0, 1e-12);
  EXPECT_NEAR(a.segment_s, 0.5, 1e-12);
  EXPECT_NEAR(a.distance_m, 2.0, 1e-12);
  EXPECT_NEAR((a.point_on_segment - Vector3d(5, 0, 2)).norm(), 0.0, 1e-12);
}

TEST(RaySegment, RayThroughTheSegmentHasZeroDistance) {
  const Vector3d dir = Vector3d(1, 1, 0).normalized();
  const auto a = closest_approach({0, 0, 0}, dir, {3, 3, -1}, {3, 3, 3});
  EXPECT_NEAR(a.distance_m, 0.0, 1e-12);
  EXPECT_NEAR(a.ray_t, 3.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(a.segment_s, 0.25, 1e-12);
}

TEST(RaySegment, ClampsToTheNearerSegmentEnd) {
  // The infinite lines meet at s = −0.5; the segment's own minimum is its end p0.
  const auto a = closest_approach({0, 0, 0}, {1, 0, 0}, {5, 1, 2}, {5, 3, 2});
  EXPECT_EQ(a.segment_s, 0.0);
  EXPECT_NEAR(a.ray_t, 5.0, 1e-12);
  EXPECT_NEAR(a.distance_m, std::sqrt(5.0), 1e-12);
  // And the far end when the segment runs the other way.
  const auto b = closest_approach({0, 0, 0}, {1, 0, 0}, {5, 3, 2}, {5, 1, 2});
  EXPECT_EQ(b.segment_s, 1.0);
  EXPECT_NEAR(b.distance_m, std::sqrt(5.0), 1e-12);
}

TEST(RaySegment, SegmentBehindTheSensorClampsToTheOrigin) {
  const auto a = closest_approach({0, 0, 0}, {1, 0, 0}, {-5, -1, 2}, {-5, 1, 2});
  EXPECT_EQ(a.ray_t, 0.0);
  EXPECT_NEAR(a.segment_s, 0.5, 1e-12);
  EXPECT_NEAR(a.distance_m, std::sqrt(29.0), 1e-12);
}

TEST(RaySegment, ParallelSegmentAheadGivesItsNearEnd) {
  const auto a = closest_approach({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {4, 1, 0});
  EXPECT_NEAR(a.distance_m, 1.0, 1e-12);
  EXPECT_NEAR(a.ray_t, 2.0, 1e-12);
  EXPECT_EQ(a.segment_s, 0.0);
  // Reversed segment: same point, now s = 1.
  const auto b = closest_approach({0, 0, 0}, {1, 0, 0}, {4, 1, 0}, {2, 1, 0});
  EXPECT_NEAR(b.ray_t, 2.0, 1e-12);
  EXPECT_EQ(b.segment_s, 1.0);
}

TEST(RaySegment, ParallelSegmentAcrossTheOriginGivesTZero) {
  const auto a = closest_approach({0, 0, 0}, {1, 0, 0}, {-1, 1, 0}, {3, 1, 0});
  EXPECT_NEAR(a.distance_m, 1.0, 1e-12);
  EXPECT_EQ(a.ray_t, 0.0);
  EXPECT_NEAR(a.segment_s, 0.25, 1e-12);
}

TEST(RaySegment, ParallelSegmentBehindGivesItsNearEnd) {
  const auto a = closest_approach({0, 0, 0}, {1, 0, 0}, {-4, 1, 0}, {-2, 1, 0});
  EXPECT_EQ(a.ray_t, 0.0);
  EXPECT_EQ(a.segment_s, 1.0);
  EXPECT_NEAR(a.distance_m, std::sqrt(5.0), 1e-12);
}

TEST(RaySegment, ZeroLengthSegmentIsAPoint) {
  const auto a = closest_approach({0, 0, 0}, {0, 0, 1}, {3, 4, 10}, {3, 4, 10});
  EXPECT_NEAR(a.distance_m, 5.0, 1e-12);
  EXPECT_NEAR(a.ray_t, 10.0, 1e-12);
}

TEST(RaySegment, KilometreRangeWireKeepsMillimetres) {
  // A 20 mm wire 1 km ahead crossing 7 mm beside the ray, at a slant.
  const Vector3d dir = Vector3d(1, 0.2, -0.05).normalized();
  const Vector3d centre = 1000.0 * dir;
  Vector3d side = dir.cross(Vector3d(0, 0, 1)).normalized();
  const Vector3d along = side.cross(dir).normalized();  // ⟂ to dir and side
  const Vector3d offset = 0.007 * side;
  const Vector3d axis = (along + 0.3 * dir).normalized();
  const auto a = closest_approach({0, 0, 0}, dir, centre + offset - 20.0 * axis,
                                  centre + offset + 30.0 * axis);
  // The common normal of dir and axis is `side` (both lie in the dir–along plane).
  EXPECT_NEAR(a.distance_m, 0.007, 1e-9);
  EXPECT_NEAR(a.ray_t, 1000.0, 1e-9);
  EXPECT_NEAR(a.segment_s, 0.4, 1e-9);
}

// Random cases against a 2-D brute-force grid over (t, s) and a fine scan over s with the exact
// clamped t: the result must be feasible, self-consistent and no worse than any sample, and no
// sample may beat it by more than the grid's Lipschitz bound.
TEST(RaySegment, RandomCasesMatchBruteForce) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const Vector3d o(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vector3d u = Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Vector3d p0(coordinate(rng), coordinate(rng), coordinate(rng));
    Vector3d p1(coordinate(rng), coordinate(rng), coordinate(rng));
    if (trial % 5 == 0) {  // nearly or exactly parallel to the ray
      const double tilt = trial % 10 == 0 ? 0.0 : 1e-9;
      p1 = p0 + coordinate(rng) * (u + tilt * Vector3d(normal(rng), normal(rng), normal(rng)));
    }
    const auto a = closest_approach(o, u, p0, p1);
    SCOPED_TRACE(::testing::Message()
                 << "trial " << trial << " o=" << o.transpose() << " u=" << u.transpose()
                 << " p0=" << p0.transpose() << " p1=" << p1.transpose());
    ASSERT_GE(a.ray_t, 0.0);
    ASSERT_GE(a.segment_s, 0.0);
    ASSERT_LE(a.segment_s, 1.0);
    EXPECT_NEAR(a.distance_m, distance_at(o, u, p0, p1, a.ray_t, a.segment_s), 1e-12);
    EXPECT_NEAR((a.point_on_segment - (p0 + a.segment_s * (p1 - p0))).norm(), 0.0, 1e-12);

    const double length = (p1 - p0).norm();
    const double t_max = std::max((p0 - o).norm(), (p1 - o).norm());
    constexpr int kGrid = 400;
    double grid_min = INFINITY;
    for (int i = 0; i <= kGrid; ++i) {
      for (int j = 0; j <= kGrid; ++j) {
        grid_min = std::min(
            grid_min, distance_at(o, u, p0, p1, t_max * i / kGrid, static_cast<double>(j) / kGrid));
      }
    }
    EXPECT_LE(a.distance_m, grid_min + 1e-12);
    EXPECT_GE(a.distance_m, grid_min - 0.5 * (t_max + length) / kGrid - 1e-12);

    constexpr int kFine = 20000;
    double fine_min = INFINITY;
    for (int j = 0; j <= kFine; ++j) {
      const double s = static_cast<double>(j) / kFine;
      const Vector3d point = p0 + s * (p1 - p0);
      fine_min = std::min(fine_min, distance_at(o, u, p0, p1, std::max(0.0, u.dot(point - o)), s));
    }
    EXPECT_LE(a.distance_m, fine_min + 1e-12);
    EXPECT_GE(a.distance_m, fine_min - 0.5 * length / kFine - 1e-12);
  }
}

}  // namespace
}  // namespace owsim
