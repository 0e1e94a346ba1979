// Protects the ray–cylinder intersection of SENSOR-SPEC §6 (eq 6.7–6.10) used for poles and
// trees: hit distances, outward normals and the ray–axis distance d on known geometry,
// tangency to ±1 µm, the caps, rays starting inside, and agreement with a brute-force march.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "geometry/cylinder.hpp"

namespace owsim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Cylinder pole() {
  Cylinder c;
  c.id = "p";
  c.base_enu_m = {10.0, 20.0, 5.0};
  c.radius_m = 0.5;
  c.height_m = 20.0;
  return c;
}

void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << actual.transpose() << " vs " << expected.transpose();
}

TEST(Cylinder, RayThroughTheAxisHitsAtDistanceMinusRadius) {
  const auto hit = intersect(pole(), {0.0, 20.0, 10.0}, {1.0, 0.0, 0.0}, 0.0, kInf);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 9.5, 1e-12);
  EXPECT_EQ(hit->face, CylinderFace::wall);
  expect_near(hit->normal, {-1, 0, 0}, 1e-12);
  EXPECT_NEAR(hit->axis_distance_m, 0.0, 1e-12);
  // From 1 km away along a diagonal.
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 1, 0).normalized();
  const auto far = intersect(pole(), Eigen::Vector3d(10, 20, 15) - 1000.0 * dir, dir, 0.0, kInf);
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->t, 999.5, 1e-9);
  expect_near(far->normal, -dir, 1e-9);
}

TEST(Cylinder, OffsetRayReportsAxisDistanceAndNormal) {
  // A horizontal ray 0.3 m north of the axis: hits where x = 10 − √(0.25 − 0.09) = 9.6.
  const auto hit = intersect(pole(), {0.0, 20.3, 10.0}, {1.0, 0.0, 0.0}, 0.0, kInf);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 9.6, 1e-12);
  EXPECT_NEAR(hit->axis_distance_m, 0.3, 1e-12);
  expect_near(hit->normal, {-0.4 / 0.5, 0.3 / 0.5, 0}, 1e-12);
  // A descending ray: d is the distance between the ray line and the vertical axis.
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 0, -0.2).normalized();
  const auto sloped = intersect(pole(), {0.0, 20.3, 12.0}, dir, 0.0, kInf);
  ASSERT_TRUE(sloped);
  EXPECT_NEAR(sloped->axis_distance_m, 0.3, 1e-12);
  EXPECT_NEAR(sloped->t * dir.x(), 9.6, 1e-12);
  EXPECT_NEAR(sloped->normal.z(), 0.0, 1e-15);
}

TEST(Cylinder, TangentRays) {
  const double eps = 1e-6;
  const auto inside = intersect(pole(), {-1000.0, 20.0 + 0.5 - eps, 10.0}, {1, 0, 0}, 0.0, kInf);
  ASSERT_TRUE(inside);
  EXPECT_NEAR(inside->axis_distance_m, 0.5 - eps, 1e-9);
  EXPECT_NEAR(inside->t, 1010.0 - std::sqrt(0.25 - std::pow(0.5 - eps, 2)), 1e-9);
  EXPECT_FALSE(intersect(pole(), {-1000.0, 20.0 + 0.5 + eps, 10.0}, {1, 0, 0}, 0.0, kInf));
  EXPECT_FALSE(intersect(pole(), {-1000.0, 20.0 - 0.5 - eps, 10.0}, {1, 0, 0}, 0.0, kInf));
}

TEST(Cylinder, CapsFromAboveAndBelow) {
  const auto top = intersect(pole(), {10.2, 20.1, 100.0}, {0, 0, -1}, 0.0, kInf);
  ASSERT_TRUE(top);
  EXPECT_EQ(top->face, CylinderFace::top);
  EXPECT_NEAR(top->t, 75.0, 1e-12);
  expect_near(top->normal, {0, 0, 1}, 0.0);
  EXPECT_NEAR(top->axis_distance_m, std::hypot(0.2, 0.1), 1e-12);
  // A helicopter looking down at 30° onto the top.
  const Eigen::Vector3d dir(std::cos(std::numbers::pi / 6), 0.0, -std::sin(std::numbers::pi / 6));
  const Eigen::Vector3d target(10.1, 20.0, 25.0);
  const auto oblique = intersect(pole(), target - 200.0 * dir, dir, 0.0, kInf);
  ASSERT_TRUE(oblique);
  EXPECT_EQ(oblique->face, CylinderFace::top);
  EXPECT_NEAR(oblique->t, 200.0, 1e-9);
  const auto bottom = intersect(pole(), {10.0, 20.0, 0.0}, {0, 0, 1}, 0.0, kInf);
  ASSERT_TRUE(bottom);
  EXPECT_EQ(bottom->face, CylinderFace::bottom);
  EXPECT_NEAR(bottom->t, 5.0, 1e-12);
  expect_near(bottom->normal, {0, 0, -1}, 0.0);
  // Just beside the top rim, looking down: misses.
  EXPECT_FALSE(intersect(pole(), {10.5001, 20.0, 100.0}, {0, 0, -1}, 0.0, kInf));
  // Passing over the top.
  EXPECT_FALSE(intersect(pole(), {0.0, 20.0, 25.01}, {1, 0, 0}, 0.0, kInf));
}

TEST(Cylinder, RaysFromInsideAndTheRangeWindow) {
  EXPECT_FALSE(intersect(pole(), {10.0, 20.0, 10.0}, {1, 0, 0}, 0.0, kInf));
  EXPECT_FALSE(intersect(pole(), {10.1, 20.0, 10.0}, {0, 0, 1}, 0.0, kInf));
  EXPECT_FALSE(intersect(pole(), {10.1, 20.0, 10.0}, {0, 0, -1}, 0.0, kInf));
  EXPECT_FALSE(intersect(pole(), {0.0, 20.0, 10.0}, {1, 0, 0}, 0.0, 9.4));
  EXPECT_FALSE(intersect(pole(), {0.0, 20.0, 10.0}, {1, 0, 0}, 9.6, kInf));  // exit is not a hit
  EXPECT_TRUE(intersect(pole(), {0.0, 20.0, 10.0}, {1, 0, 0}, 9.5, 9.5));
  EXPECT_FALSE(intersect(pole(), {0.0, 20.0, 10.0}, {-1, 0, 0}, 0.0, kInf));  // facing away
}

TEST(Cylinder, Bounds) {
  const Eigen::AlignedBox3d box = bounds(pole());
  expect_near(box.min(), {9.5, 19.5, 5.0}, 0.0);
  expect_near(box.max(), {10.5, 20.5, 25.0}, 0.0);
}

// Brute force: march along the ray and report the first step inside the solid.
std::optional<double> march(const Cylinder& c, const Eigen::Vector3d& origin,
                            const Eigen::Vector3d& dir, double length, double step) {
  for (double t = 0.0; t <= length; t += step) {
    const Eigen::Vector3d p = origin + t * dir - c.base_enu_m;
    if (p.z() >= 0.0 && p.z() <= c.height_m &&
        p.x() * p.x() + p.y() * p.y() <= c.radius_m * c.radius_m) {
      return t;
    }
  }
  return std::nullopt;
}

TEST(Cylinder, RandomRaysAgreeWithABruteForceMarch) {
  Cylinder c;
  c.base_enu_m = {0.0, 0.0, 0.0};
  c.radius_m = 1.5;
  c.height_m = 8.0;
  std::mt19937_64 engine(20240607);  // the engine's output sequence is fixed by the standard
  const auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
  };
  const double step = 2e-4, margin = 2e-3;
  int hits = 0, misses = 0, caps = 0, skipped = 0;
  for (int ray = 0; ray < 400; ++ray) {
    const Eigen::Vector3d origin(uniform(-20, 20), uniform(-20, 20), uniform(-5, 30));
    if (std::hypot(origin.x(), origin.y()) <= c.radius_m + 0.1) continue;  // start outside
    const Eigen::Vector3d target(uniform(-2.5, 2.5), uniform(-2.5, 2.5), uniform(-1, 9));
    const Eigen::Vector3d dir = (target - origin).normalized();
    const double length = (target - origin).norm() + 5.0;
    const auto hit = intersect(c, origin, dir, 0.0, length);
    // Skip near-tangent rays and hits within the margin of a rim: the march's step cannot see
    // those short chords.
    const Eigen::Vector2d d_h = dir.head<2>();
    const Eigen::Vector2d closest =
        origin.head<2>() - origin.head<2>().dot(d_h) / d_h.squaredNorm() * d_h;
    bool near_edge = std::abs(closest.norm() - c.radius_m) < margin;
    if (hit) {
      const Eigen::Vector3d p = origin + hit->t * dir;
      near_edge = near_edge ||
                  (hit->face == CylinderFace::wall ? std::min(p.z(), c.height_m - p.z()) < margin
                                                   : c.radius_m - p.head<2>().norm() < margin);
    }
    if (near_edge) {
      ++skipped;
      continue;
    }
    const auto marched = march(c, origin, dir, length, step);
    ASSERT_EQ(hit.has_value(), marched.has_value())
        << "ray " << ray << " origin " << origin.transpose() << " dir " << dir.transpose();
    if (hit) {
      EXPECT_NEAR(*marched, hit->t, step * 1.01) << "ray " << ray;
      EXPECT_NEAR(hit->axis_distance_m, closest.norm(), 1e-9);
      ++hits;
      if (hit->face != CylinderFace::wall) ++caps;
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 50);
  EXPECT_GT(caps, 10);
  EXPECT_LT(skipped, 20);
}

}  // namespace
}  // namespace owsim
