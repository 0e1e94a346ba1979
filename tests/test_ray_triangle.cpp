// Protects the double-precision ray–triangle test (geometry/ray_triangle.hpp) that turns the
// engine's float terrain hits into exact ranges and that the brute-force tracer uses: known hits
// and misses, edges and corners, both faces, the [t_min, t_max] window, and agreement with an
// independent plane-then-inside implementation over seeded random rays.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "geometry/error.hpp"
#include "geometry/ray_triangle.hpp"

namespace owsim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

const Eigen::Vector3d kV0(0.0, 0.0, 0.0);
const Eigen::Vector3d kV1(10.0, 0.0, 0.0);
const Eigen::Vector3d kV2(0.0, 10.0, 0.0);

std::optional<TriangleHit> down_at(double e, double n, double height = 5.0) {
  return intersect_triangle(Eigen::Vector3d(e, n, height), -Eigen::Vector3d::UnitZ(), kV0, kV1, kV2,
                            0.0, kInfinity);
}

TEST(RayTriangle, VerticalRayHitsInsideWithExactRangeAndUpNormal) {
  const auto hit = down_at(2.0, 3.0, 7.5);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 7.5);
  // (v1 − v0) × (v2 − v0) is +z for this counter-clockwise triangle.
  EXPECT_NEAR((hit->normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
}

TEST(RayTriangle, MissesOutsideTheTriangle) {
  EXPECT_FALSE(down_at(-0.1, 3.0));
  EXPECT_FALSE(down_at(3.0, -0.1));
  EXPECT_FALSE(down_at(6.0, 6.0));  // beyond the hypotenuse e + n = 10
  EXPECT_FALSE(down_at(20.0, 20.0));
}

TEST(RayTriangle, EdgesAndCornersCount) {
  EXPECT_TRUE(down_at(5.0, 0.0));  // edge v0–v1
  EXPECT_TRUE(down_at(0.0, 5.0));  // edge v0–v2
  EXPECT_TRUE(down_at(5.0, 5.0));  // hypotenuse, exact in binary
  EXPECT_TRUE(down_at(0.0, 0.0));  // corners
  EXPECT_TRUE(down_at(10.0, 0.0));
  EXPECT_TRUE(down_at(0.0, 10.0));
}

TEST(RayTriangle, BothFacesHitAndTheNormalKeepsItsWinding) {
  const auto from_below = intersect_triangle(Eigen::Vector3d(1.0, 1.0, -4.0),
                                             Eigen::Vector3d::UnitZ(), kV0, kV1, kV2, 0.0, kInfinity);
  ASSERT_TRUE(from_below);
  EXPECT_DOUBLE_EQ(from_below->t, 4.0);
  EXPECT_NEAR((from_below->normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  // Reversed winding flips the normal, not the hit.
  const auto reversed = intersect_triangle(Eigen::Vector3d(1.0, 1.0, 4.0),
                                           -Eigen::Vector3d::UnitZ(), kV0, kV2, kV1, 0.0, kInfinity);
  ASSERT_TRUE(reversed);
  EXPECT_NEAR((reversed->normal + Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
}

TEST(RayTriangle, RangeWindowAndDirection) {
  const Eigen::Vector3d origin(1.0, 1.0, 5.0);
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  EXPECT_FALSE(intersect_triangle(origin, -down, kV0, kV1, kV2, 0.0, kInfinity));   // behind the ray
  EXPECT_FALSE(intersect_triangle(origin, down, kV0, kV1, kV2, 0.0, 4.999));   // beyond t_max
  EXPECT_FALSE(intersect_triangle(origin, down, kV0, kV1, kV2, 5.001, kInfinity));  // before t_min
  EXPECT_TRUE(intersect_triangle(origin, down, kV0, kV1, kV2, 5.0, 5.0));      // window is closed
}

TEST(RayTriangle, ParallelAndDegenerateNeverHit) {
  // A ray in the triangle's plane.
  EXPECT_FALSE(intersect_triangle(Eigen::Vector3d(-5.0, 1.0, 0.0), Eigen::Vector3d::UnitX(), kV0,
                                  kV1, kV2, 0.0, kInfinity));
  // A ray parallel above it.
  EXPECT_FALSE(intersect_triangle(Eigen::Vector3d(-5.0, 1.0, 1.0), Eigen::Vector3d::UnitX(), kV0,
                                  kV1, kV2, 0.0, kInfinity));
  // Collinear corners.
  EXPECT_FALSE(intersect_triangle(Eigen::Vector3d(1.0, 0.0, 5.0), -Eigen::Vector3d::UnitZ(), kV0,
                                  kV1, Eigen::Vector3d(20.0, 0.0, 0.0), 0.0, kInfinity));
}

TEST(RayTriangle, OblongRayAtKilometreRangeKeepsMillimetres) {
  // A terrain triangle 1.2 km away seen at 3° grazing incidence.
  const Eigen::Vector3d a(1000.0, -50.0, 0.0);
  const Eigen::Vector3d b(1300.0, -50.0, 0.0);
  const Eigen::Vector3d c(1000.0, 250.0, 0.0);
  const double angle = 3.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d dir(std::cos(angle), 0.0, -std::sin(angle));
  const double expected = 60.0 / std::sin(angle);  // from 60 m up
  const Eigen::Vector3d origin = Eigen::Vector3d(1100.0, 0.0, 0.0) - expected * dir;
  const auto hit = intersect_triangle(origin, dir, a, b, c, 0.0, kInfinity);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, expected, 1e-9);
}

// A ray through an edge or corner two triangles share hits at least one of them: the terrain
// mesh is closed for the brute-force tracer even at grazing incidence from a kilometre away.
TEST(RayTriangle, SharedEdgesAndCornersLeaveNoGap) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // A 150 m lattice cell split along its SW–NE diagonal, with uneven corner heights.
  for (int trial = 0; trial < 5000; ++trial) {
    const double e0 = 150.0 * std::floor(20.0 * unit(rng) - 10.0);
    const double n0 = 150.0 * std::floor(20.0 * unit(rng) - 10.0);
    const Eigen::Vector3d sw(e0, n0, 100.0 * unit(rng));
    const Eigen::Vector3d se(e0 + 150.0, n0, 100.0 * unit(rng));
    const Eigen::Vector3d ne(e0 + 150.0, n0 + 150.0, 100.0 * unit(rng));
    const Eigen::Vector3d nw(e0, n0 + 150.0, 100.0 * unit(rng));
    const Eigen::Vector3d target = trial % 4 == 0 ? sw : sw + unit(rng) * (ne - sw);
    const double elevation = (1.0 + 9.0 * unit(rng)) * std::numbers::pi / 180.0;
    const double bearing = 2.0 * std::numbers::pi * unit(rng);
    const Eigen::Vector3d dir(std::cos(elevation) * std::sin(bearing),
                              std::cos(elevation) * std::cos(bearing), -std::sin(elevation));
    const Eigen::Vector3d origin = target - (100.0 + 1100.0 * unit(rng)) * dir;
    const auto lower = intersect_triangle(origin, dir, sw, se, ne, 0.0, kInfinity);
    const auto upper = intersect_triangle(origin, dir, sw, ne, nw, 0.0, kInfinity);
    ASSERT_TRUE(lower || upper) << "trial " << trial;
    const double t = lower ? lower->t : upper->t;
    EXPECT_NEAR((origin + t * dir - target).norm(), 0.0, 1e-6) << "trial " << trial;
  }
}

// An independent implementation: the ray meets the plane at t = n·(v0 − o) / n·d, and the point
// is inside when it lies on the inner side of all three edges (same-sign edge cross products).
struct Reference {
  bool hit = false;
  double t = 0.0;
  double edge_margin = 0.0;  // smallest distance of the plane point to an edge line
};

Reference reference_intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                              const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                              const Eigen::Vector3d& v2) {
  const Eigen::Vector3d n = (v1 - v0).cross(v2 - v0).normalized();
  const double along = n.dot(d);
  if (along == 0.0) return {};
  const double t = n.dot(v0 - o) / along;
  const Eigen::Vector3d p = o + t * d;
  const Eigen::Vector3d corners[3] = {v0, v1, v2};
  Reference result{t >= 0.0, t, kInfinity};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d& from = corners[i];
    const Eigen::Vector3d& to = corners[(i + 1) % 3];
    const Eigen::Vector3d edge = to - from;
    const double side = n.dot(edge.cross(p - from));  // > 0 inside for counter-clockwise
    result.edge_margin = std::min(result.edge_margin, std::abs(side) / edge.norm());
    if (side < 0.0) result.hit = false;
  }
  return result;
}

TEST(RayTriangle, AgreesWithPlaneThenInsideOverRandomRays) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> coordinate(-100.0, 100.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  int hits = 0;
  int compared = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector3d v0(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d v1(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d v2(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d origin(3 * coordinate(rng), 3 * coordinate(rng), 3 * coordinate(rng));
    // Aim at a random point near the triangle so about half the rays hit.
    const double u = std::uniform_real_distribution<double>(-0.3, 1.0)(rng);
    const double v = std::uniform_real_distribution<double>(-0.3, 1.0)(rng);
    const Eigen::Vector3d target = v0 + u * (v1 - v0) + v * (v2 - v0);
    const Eigen::Vector3d dir = (target - origin).normalized();
    const Eigen::Vector3d area = (v1 - v0).cross(v2 - v0);
    if (area.norm() < 1.0 || std::abs(area.normalized().dot(dir)) < 1e-3) continue;
    const Reference expected = reference_intersect(origin, dir, v0, v1, v2);
    if (expected.edge_margin < 1e-6) continue;  // too close to an edge to call
    const auto hit = intersect_triangle(origin, dir, v0, v1, v2, 0.0, kInfinity);
    ++compared;
    ASSERT_EQ(hit.has_value(), expected.hit) << "trial " << trial;
    if (!hit) continue;
    ++hits;
    EXPECT_NEAR(hit->t, expected.t, 1e-9 * std::max(1.0, expected.t)) << "trial " << trial;
    EXPECT_NEAR((hit->normal - area.normalized()).norm(), 0.0, 1e-12);
  }
  EXPECT_GT(compared, 15000);
  EXPECT_GT(hits, 5000);
  EXPECT_LT(hits, compared - 5000);
}

// The engine traces meshes through their precomputed frames: every hit, miss and plane fallback
// must be the vertex path's to the bit (the brute-force tracer takes the vertices).
TEST(RayTriangle, PrecomputedFramesGiveTheVertexPathsBits) {
  std::mt19937_64 random(4601);
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  std::normal_distribution<double> normal;
  TriangleMesh mesh;
  for (int i = 0; i < 300; ++i) {
    mesh.vertices.emplace_back(coordinate(random), coordinate(random), 0.1 * coordinate(random));
  }
  for (std::uint32_t i = 0; i + 2 < 300; i += 3) mesh.triangles.push_back({i, i + 1, i + 2});
  const std::vector<TriangleFrame> frames = triangle_frames(mesh);
  ASSERT_EQ(frames.size(), mesh.triangles.size());
  int hits = 0;
  for (int draw = 0; draw < 20000; ++draw) {
    const std::size_t index = static_cast<std::size_t>(draw) % mesh.triangles.size();
    const auto& triangle = mesh.triangles[index];
    const Eigen::Vector3d& v0 = mesh.vertices[triangle[0]];
    const Eigen::Vector3d& v1 = mesh.vertices[triangle[1]];
    const Eigen::Vector3d& v2 = mesh.vertices[triangle[2]];
    // Aimed near the triangle (inside about half the time), from up to a kilometre away.
    const Eigen::Vector3d target = (v0 + v1 + v2) / 3.0 + 0.6 * normal(random) * (v1 - v0);
    const Eigen::Vector3d origin =
        target + Eigen::Vector3d(normal(random), normal(random), 2.0 + normal(random)) * 300.0;
    const Eigen::Vector3d dir = (target - origin).normalized();
    const auto by_vertices = intersect_triangle(origin, dir, v0, v1, v2, 0.0, 1e9);
    const auto by_frame = intersect_triangle(origin, dir, frames[index], 0.0, 1e9);
    ASSERT_EQ(by_vertices.has_value(), by_frame.has_value()) << draw;
    if (by_vertices) {
      ++hits;
      ASSERT_EQ(by_vertices->t, by_frame->t);
      ASSERT_EQ(by_vertices->normal, by_frame->normal);
    }
    const TriangleHit exact_vertices = exact_mesh_hit(mesh, index, origin, dir);
    const TriangleHit exact_frames = exact_mesh_hit(frames, index, origin, dir);
    ASSERT_EQ(exact_vertices.t, exact_frames.t);
    ASSERT_EQ(exact_vertices.normal, exact_frames.normal);
  }
  EXPECT_GT(hits, 4000);
  EXPECT_LT(hits, 16000);
}

// The engine's level ground takes every ray's range from first_triangle_hits over a block: each
// lane must be intersect_triangle's bits (a hit's t, or none), the first triangle that accepts the
// ray winning — over level and sloping triangles, rays aimed at their shared diagonal, rays in
// their plane, and rays whose window ends before the triangle.
TEST(RayTriangle, BlockOfRaysGivesTheOneRayTestsBitsFirstTriangleFirst) {
  std::mt19937_64 random(4602);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // A flat terrain's two triangles over a 6 km × 5 km region (as geometry/terrain.cpp makes them),
  // then a sloping pair sharing the same diagonal.
  const Eigen::Vector3d lo(-2500.0, -2000.0, 412.5), hi(3500.0, 3000.0, 412.5);
  const Eigen::Vector3d c1(hi.x(), lo.y(), lo.z()), c3(lo.x(), hi.y(), lo.z());
  const std::vector<std::vector<TriangleFrame>> sets = {
      {triangle_frame(lo, c1, hi), triangle_frame(lo, hi, c3)},
      {triangle_frame(lo, c1 + Eigen::Vector3d(0, 0, 90), hi + Eigen::Vector3d(0, 0, 40)),
       triangle_frame(lo, hi + Eigen::Vector3d(0, 0, 40), c3 - Eigen::Vector3d(0, 0, 25))}};
  int hits = 0, seconds = 0, diagonal = 0, lanes = 0;
  for (const auto& triangles : sets) {
    for (int block = 0; block < 200; ++block) {
      RayArrays rays;
      const std::size_t n = 1 + static_cast<std::size_t>(unit(random) * (RayArrays::kCapacity - 1));
      for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d origin(3000.0 * normal(random), 3000.0 * normal(random),
                                     lo.z() + 300.0 * normal(random));
        // Aimed at the diagonal in one lane of four (within millimetres), else anywhere near.
        const double along = unit(random);
        Eigen::Vector3d target = lo + along * (hi - lo);
        if (i % 4 != 0) {
          target += Eigen::Vector3d(2500.0 * normal(random), 2500.0 * normal(random), 0.0);
        } else {
          target += Eigen::Vector3d(1e-3 * normal(random), 1e-3 * normal(random), 0.0);
        }
        Eigen::Vector3d dir = (target - origin).normalized();
        if (i % 16 == 5) dir.z() = 0.0;  // level rays: in the plane or parallel to it
        if (i % 16 == 9) dir = -dir;     // away from the ground
        for (int axis = 0; axis < 3; ++axis) {
          rays.origin[axis][i] = origin[axis];
          rays.dir[axis][i] = dir[axis];
        }
        rays.t_max[i] = i % 8 == 3 ? 500.0 * unit(random) : 1e4;
      }
      std::array<double, RayArrays::kCapacity> ranges;
      std::array<std::int64_t, RayArrays::kCapacity> which;
      first_triangle_hits(triangles, rays, n, ranges.data(), which.data());
      for (std::size_t i = 0; i < n; ++i) {
        ++lanes;
        const Eigen::Vector3d origin(rays.origin[0][i], rays.origin[1][i], rays.origin[2][i]);
        const Eigen::Vector3d dir(rays.dir[0][i], rays.dir[1][i], rays.dir[2][i]);
        std::optional<TriangleHit> expected;
        std::size_t expected_index = 0;
        for (std::size_t k = 0; k < triangles.size() && !expected; ++k) {
          expected = intersect_triangle(origin, dir, triangles[k], 0.0, rays.t_max[i]);
          expected_index = k;
        }
        if (!expected) {
          ASSERT_TRUE(std::isnan(ranges[i])) << "block " << block << " lane " << i;
          continue;
        }
        ++hits;
        seconds += expected_index == 1 ? 1 : 0;
        diagonal += i % 4 == 0 ? 1 : 0;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(ranges[i]),
                  std::bit_cast<std::uint64_t>(expected->t))
            << "block " << block << " lane " << i;
        ASSERT_EQ(which[i], expected_index) << "block " << block << " lane " << i;
      }
    }
  }
  EXPECT_GT(hits, lanes / 4);
  EXPECT_GT(seconds, hits / 4);
  EXPECT_GT(diagonal, hits / 8);
}

TEST(RayTriangle, BlockOfRaysRefusesMoreThanABlock) {
  RayArrays rays;
  std::array<double, 1> ranges;
  std::array<std::int64_t, 1> which;
  const std::vector<TriangleFrame> one = {triangle_frame(kV0, kV1, kV2)};
  EXPECT_THROW(
      first_triangle_hits(one, rays, RayArrays::kCapacity + 1, ranges.data(), which.data()), Error);
}

}  // namespace
}  // namespace owsim
