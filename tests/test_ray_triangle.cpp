// Protects the double-precision ray–triangle test (geometry/ray_triangle.hpp) that turns the
// engine's float terrain hits into exact ranges and that the brute-force tracer uses: known hits
// and misses, edges and corners, both faces, the [t_min, t_max] window, and agreement with an
// independent plane-then-inside implementation over seeded random rays.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "geometry/ray_triangle.hpp"

namespace owsim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const Eigen::Vector3d kV0(0.0, 0.0, 0.0);
const Eigen::Vector3d kV1(10.0, 0.0, 0.0);
const Eigen::Vector3d kV2(0.0, 10.0, 0.0);

std::optional<TriangleHit> down_at(double e, double n, double height = 5.0) {
  return intersect_triangle(Eigen::Vector3d(e, n, height), -Eigen::Vector3d::UnitZ(), kV0, kV1, kV2,
                            0.0, kInf);
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
                                             Eigen::Vector3d::UnitZ(), kV0, kV1, kV2, 0.0, kInf);
  ASSERT_TRUE(from_below);
  EXPECT_DOUBLE_EQ(from_below->t, 4.0);
  EXPECT_NEAR((from_below->normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  // Reversed winding flips the normal, not the hit.
  const auto reversed = intersect_triangle(Eigen::Vector3d(1.0, 1.0, 4.0),
                                           -Eigen::Vector3d::UnitZ(), kV0, kV2, kV1, 0.0, kInf);
  ASSERT_TRUE(reversed);
  EXPECT_NEAR((reversed->normal + Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
}

TEST(RayTriangle, RangeWindowAndDirection) {
  const Eigen::Vector3d origin(1.0, 1.0, 5.0);
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  EXPECT_FALSE(intersect_triangle(origin, -down, kV0, kV1, kV2, 0.0, kInf));   // behind the ray
  EXPECT_FALSE(intersect_triangle(origin, down, kV0, kV1, kV2, 0.0, 4.999));   // beyond t_max
  EXPECT_FALSE(intersect_triangle(origin, down, kV0, kV1, kV2, 5.001, kInf));  // before t_min
  EXPECT_TRUE(intersect_triangle(origin, down, kV0, kV1, kV2, 5.0, 5.0));      // window is closed
}

TEST(RayTriangle, ParallelAndDegenerateNeverHit) {
  // A ray in the triangle's plane.
  EXPECT_FALSE(intersect_triangle(Eigen::Vector3d(-5.0, 1.0, 0.0), Eigen::Vector3d::UnitX(), kV0,
                                  kV1, kV2, 0.0, kInf));
  // A ray parallel above it.
  EXPECT_FALSE(intersect_triangle(Eigen::Vector3d(-5.0, 1.0, 1.0), Eigen::Vector3d::UnitX(), kV0,
                                  kV1, kV2, 0.0, kInf));
  // Collinear corners.
  EXPECT_FALSE(intersect_triangle(Eigen::Vector3d(1.0, 0.0, 5.0), -Eigen::Vector3d::UnitZ(), kV0,
                                  kV1, Eigen::Vector3d(20.0, 0.0, 0.0), 0.0, kInf));
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
  const auto hit = intersect_triangle(origin, dir, a, b, c, 0.0, kInf);
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
    const auto lower = intersect_triangle(origin, dir, sw, se, ne, 0.0, kInf);
    const auto upper = intersect_triangle(origin, dir, sw, ne, nw, 0.0, kInf);
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
  Reference result{t >= 0.0, t, kInf};
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
    const auto hit = intersect_triangle(origin, dir, v0, v1, v2, 0.0, kInf);
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

}  // namespace
}  // namespace owsim
