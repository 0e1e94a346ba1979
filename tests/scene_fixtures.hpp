#pragma once
// Seeded random scenes, poses and rays for the engine tests (test_embree_scene, test_frame_tracer,
// test_frame_simulator, test_wire_detection): catenary spans (single, tri and sept layouts, wire
// diameters 5–30 mm) at 20–1200 m from a sensor, trees, flat terrain or a small sloped grid, and
// rays aimed at the wires the way the hard cases happen — across them, grazing the capture
// distance r_wire + r_beam(R), and nearly parallel to them (edge-on). Test code only: the draws
// come from std::mt19937_64 seeded by each test, so every run sees the same scenes.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geometry/conductor_layout.hpp"
#include "geometry/scene.hpp"
#include "geometry/span.hpp"
#include "sensor/beam.hpp"
#include "sensor/mounting.hpp"
#include "sensor/pose_source.hpp"
#include "sensor/pulse_candidates.hpp"

namespace owsim::test {

using Rng = std::mt19937_64;

inline double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
inline int uniform_int(Rng& rng, int lo, int hi) {  // inclusive
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}
inline double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// A unit vector perpendicular to `v` (any one).
inline Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& v) {
  const Eigen::Vector3d other =
      std::abs(v.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return v.cross(other).normalized();
}

struct RandomSceneParams {
  int spans = 5;
  int trees = 8;
  bool sloped_grid = false;   // false: flat terrain at a random height
  double min_range_m = 20.0;  // horizontal distance of a span's nearest part from the sensor
  double max_range_m = 1200.0;
  double extent_m = 1800.0;  // the terrain covers the sensor ± extent
};

struct RandomScene {
  Scene scene;
  Eigen::Vector3d sensor_enu_m = Eigen::Vector3d::Zero();
  Eigen::AlignedBox2d region;  // what the engine meshes
};

// Flat terrain at a random height, or a planar sloped grid (slope up to 4 %) with ±3 m bumps,
// 150 m cells, around the origin.
inline Terrain random_terrain(Rng& rng, bool sloped_grid, double extent_m) {
  Terrain terrain;
  terrain.reflectivity = uniform(rng, 0.1, 0.3);
  if (!sloped_grid) {
    terrain.kind = TerrainKind::flat;
    terrain.flat_u_m = uniform(rng, -50.0, 300.0);
    return terrain;
  }
  terrain.kind = TerrainKind::grid;
  HeightGrid& grid = terrain.grid;
  grid.cellsize_m = 150.0;
  grid.ncols = static_cast<int>(std::ceil(2.0 * extent_m / grid.cellsize_m)) + 1;
  grid.nrows = grid.ncols;
  grid.x_west_m = -0.5 * (grid.ncols - 1) * grid.cellsize_m;
  grid.y_south_m = grid.x_west_m;
  const double base = uniform(rng, 0.0, 400.0);
  const double slope_e = uniform(rng, -0.04, 0.04);
  const double slope_n = uniform(rng, -0.04, 0.04);
  grid.heights.resize(static_cast<std::size_t>(grid.ncols * grid.nrows));
  for (int row = 0; row < grid.nrows; ++row) {
    for (int col = 0; col < grid.ncols; ++col) {
      grid.heights[static_cast<std::size_t>(row * grid.ncols + col)] =
          base + slope_e * grid.east_of_col_m(col) + slope_n * grid.north_of_row_m(row) +
          uniform(rng, -3.0, 3.0);
    }
  }
  return terrain;
}

// Spans whose midpoints lie at horizontal distances min_range..max_range from a sensor standing
// 25–90 m above the ground at the origin (wire height, the hazard case), in random directions
// and orientations; trees 40–800 m away.
inline RandomScene random_scene(std::uint64_t seed, const RandomSceneParams& params = {}) {
  Rng rng(seed);
  RandomScene result;
  Scene& scene = result.scene;
  scene.terrain = random_terrain(rng, params.sloped_grid, params.extent_m);
  result.sensor_enu_m =
      Eigen::Vector3d(0.0, 0.0, scene.terrain.height_at(0.0, 0.0) + uniform(rng, 25.0, 90.0));
  result.region =
      Eigen::AlignedBox2d(Eigen::Vector2d(-1500.0, -1500.0), Eigen::Vector2d(1500.0, 1500.0));

  const LayoutKind layouts[3] = {LayoutKind::single, LayoutKind::tri, LayoutKind::sept};
  for (int s = 0; s < params.spans; ++s) {
    SpanSpec spec;
    spec.id = "span" + std::to_string(s);
    const double range =
        params.min_range_m + (params.max_range_m - params.min_range_m) *
                                 std::pow(uniform(rng, 0.0, 1.0), 1.5);  // more near than far
    const double bearing = uniform(rng, 0.0, 2.0 * std::numbers::pi);
    const Eigen::Vector2d middle = range * Eigen::Vector2d(std::sin(bearing), std::cos(bearing));
    // Mostly across the line of sight, sometimes along it.
    const double across = bearing + std::numbers::pi / 2 + uniform(rng, -1.2, 1.2);
    const Eigen::Vector2d along(std::sin(across), std::cos(across));
    const double length = uniform(rng, 60.0, 400.0);
    spec.from_en = middle - 0.5 * length * along;
    spec.to_en = middle + 0.5 * length * along;
    // Keep the sensor clear of every conductor: move the span out if it passes too close.
    const Eigen::Vector2d closest =
        spec.from_en + std::clamp(-spec.from_en.dot(along), 0.0, length) * along;
    if (closest.norm() < params.min_range_m) {
      const Eigen::Vector2d away =
          closest.norm() > 1e-6 ? closest.normalized() : Eigen::Vector2d(1.0, 0.0);
      const Eigen::Vector2d shift = (params.min_range_m + 15.0 - closest.norm()) * away;
      spec.from_en += shift;
      spec.to_en += shift;
    }
    spec.support_height_1_m = uniform(rng, 20.0, 60.0);
    spec.support_height_2_m = uniform(rng, 20.0, 60.0);
    const LayoutKind layout = layouts[uniform_int(rng, 0, 2)];
    spec.offsets = conductor_offsets(layout);
    double lowest_offset = 0.0;
    for (const ConductorOffset& offset : spec.offsets)
      lowest_offset = std::min(lowest_offset, offset.vertical_m);
    const double low_support = std::min(spec.support_height_1_m, spec.support_height_2_m);
    spec.lowest_point_m =
        uniform(rng, std::max(-lowest_offset + 6.0, 0.3 * low_support), low_support - 0.5);
    spec.conductor_diameter_m = uniform(rng, 0.005, 0.030);
    spec.conductor_reflectivity = uniform(rng, 0.2, 0.6);
    spec.pole_diameter_m = uniform(rng, 0.3, 1.0);
    SpanObjects objects = build_span(spec, scene.terrain);
    for (Conductor& c : objects.conductors) scene.conductors.push_back(std::move(c));
    for (Cylinder& p : objects.poles) scene.cylinders.push_back(std::move(p));
  }
  for (int t = 0; t < params.trees; ++t) {
    Cylinder tree;
    tree.id = "tree" + std::to_string(t);
    tree.surface = SurfaceClass::tree;
    const double range = uniform(rng, 40.0, 800.0);
    const double bearing = uniform(rng, 0.0, 2.0 * std::numbers::pi);
    const double e = range * std::sin(bearing);
    const double n = range * std::cos(bearing);
    tree.base_enu_m = Eigen::Vector3d(e, n, scene.terrain.height_at(e, n));
    tree.radius_m = uniform(rng, 1.0, 5.0);
    tree.height_m = uniform(rng, 5.0, 25.0);
    tree.reflectivity = uniform(rng, 0.1, 0.4);
    scene.cylinders.push_back(tree);
  }
  return result;
}

// The capture distance of the §7 wire rule at range R: r_wire + r_beam(R).
inline double capture_distance_m(const Conductor& conductor, double range_m,
                                 const BeamParams& beam) {
  return conductor.radius_m + beam_radius_m(range_m, beam);
}

// True when `point` lies over the terrain (inside a grid's extent) at least 1 m above it.
inline bool above_ground(const Terrain& terrain, const Eigen::Vector3d& point) {
  if (terrain.kind == TerrainKind::grid) {
    const HeightGrid& grid = terrain.grid;
    if (point.x() < grid.x_west_m || point.x() > grid.x_east_m() || point.y() < grid.y_south_m ||
        point.y() > grid.y_north_m()) {
      return false;
    }
  }
  return point.z() > terrain.height_at(point.x(), point.y()) + 1.0;
}

// How a ray was aimed, so a test can count what it covered.
enum class AimKind { across, grazing_inside, grazing_outside, edge_on, end_cap, random };

struct AimedRay {
  PulseRay ray;
  AimKind kind = AimKind::random;
  std::uint32_t conductor = 0;  // the conductor aimed at (across, grazing, edge-on, end cap)
};

// A ray from `origin` through the point `target + offset`, `offset` chosen perpendicular to both
// the line of sight and the wire so the closest approach to the wire is |offset| (to first order).
inline PulseRay ray_past(const Eigen::Vector3d& origin, const Eigen::Vector3d& target,
                         const Eigen::Vector3d& wire_dir, double miss_m, double side_angle) {
  const Eigen::Vector3d sight = (target - origin).normalized();
  Eigen::Vector3d normal = sight.cross(wire_dir);
  if (normal.norm() < 1e-9) normal = any_perpendicular(sight);
  normal.normalize();
  const Eigen::Vector3d binormal = sight.cross(normal).normalized();
  const Eigen::Vector3d offset =
      miss_m * (std::cos(side_angle) * normal + std::sin(side_angle) * binormal);
  return PulseRay{origin, (target + offset - origin).normalized()};
}

// Rays aimed at the scene's wires from origins near `sensor`:
//   across          — through a random point of a random segment, missing the axis by
//                     0..1.2 × the capture distance;
//   grazing_inside  — missing by (1 − 1e-4..1e-6) × the capture distance, straight across the
//                     wire (the closest approach is then the aimed point);
//   grazing_outside — the same just outside (1 + 1e-6..1e-4);
//   edge_on         — from a point on the prolongation of a segment 20–1200 m away, within
//                     0–2° of the wire's direction, passing within the capture distance;
//   end_cap         — at points just beyond a conductor's free end (the round cap);
//   random          — anywhere in the ±45° cone about a random wire point (ground, trees).
// Rays whose origin would lie underground or within 1 m of a conductor are not made.
inline std::vector<AimedRay> rays_at_wires(const Scene& scene, const Eigen::Vector3d& sensor,
                                           const BeamParams& beam, Rng& rng, int count) {
  std::vector<AimedRay> rays;
  rays.reserve(static_cast<std::size_t>(count));
  const AimKind kinds[6] = {AimKind::across,  AimKind::grazing_inside, AimKind::grazing_outside,
                            AimKind::edge_on, AimKind::end_cap,        AimKind::random};
  const double weights[6] = {0.35, 0.15, 0.1, 0.2, 0.1, 0.1};
  std::discrete_distribution<int> pick_kind(std::begin(weights), std::end(weights));
  while (static_cast<int>(rays.size()) < count) {
    const AimKind kind = kinds[pick_kind(rng)];
    const auto w = static_cast<std::uint32_t>(
        uniform_int(rng, 0, static_cast<int>(scene.conductors.size()) - 1));
    const Conductor& conductor = scene.conductors[w];
    const auto& points = conductor.points_enu_m;
    const int segments = static_cast<int>(points.size()) - 1;
    const auto k = static_cast<std::size_t>(uniform_int(rng, 0, segments - 1));
    const Eigen::Vector3d p0 = points[k];
    const Eigen::Vector3d p1 = points[k + 1];
    const Eigen::Vector3d wire_dir = (p1 - p0).normalized();
    Eigen::Vector3d origin =
        sensor +
        Eigen::Vector3d(uniform(rng, -5.0, 5.0), uniform(rng, -5.0, 5.0), uniform(rng, -5.0, 5.0));
    AimedRay aimed;
    aimed.kind = kind;
    aimed.conductor = w;
    switch (kind) {
      case AimKind::across: {
        const Eigen::Vector3d target = p0 + uniform(rng, 0.0, 1.0) * (p1 - p0);
        const double limit = capture_distance_m(conductor, (target - origin).norm(), beam);
        aimed.ray = ray_past(origin, target, wire_dir, uniform(rng, 0.0, 1.2) * limit,
                             uniform(rng, 0.0, 2.0 * std::numbers::pi));
        break;
      }
      case AimKind::grazing_inside:
      case AimKind::grazing_outside: {
        const Eigen::Vector3d target = p0 + uniform(rng, 0.2, 0.8) * (p1 - p0);
        const Eigen::Vector3d sight = (target - origin).normalized();
        // Square the line of sight to the wire so the closest approach is the aimed point.
        const Eigen::Vector3d across_dir = (sight - sight.dot(wire_dir) * wire_dir).normalized();
        origin = target - (target - origin).norm() * across_dir;
        const double range = (target - origin).norm();
        const double limit = capture_distance_m(conductor, range, beam);
        const double epsilon = std::pow(10.0, uniform(rng, -6.0, -4.0));
        const double miss =
            kind == AimKind::grazing_inside ? limit * (1.0 - epsilon) : limit * (1.0 + epsilon);
        const Eigen::Vector3d side = wire_dir.cross(across_dir).normalized();
        aimed.ray = PulseRay{origin, across_dir};
        aimed.ray.origin_enu_m += miss * side;
        break;
      }
      case AimKind::edge_on: {
        const double back = uniform(rng, 20.0, 1200.0);
        const Eigen::Vector3d target = p0 + uniform(rng, 0.0, 1.0) * (p1 - p0);
        const double tilt = radians(uniform(rng, 0.0, 2.0));
        const Eigen::Vector3d turn = any_perpendicular(wire_dir);
        const double spin = uniform(rng, 0.0, 2.0 * std::numbers::pi);
        const Eigen::Vector3d sideways =
            Eigen::AngleAxisd(spin, wire_dir) * turn;  // a random direction across the wire
        const Eigen::Vector3d approach =
            (std::cos(tilt) * wire_dir + std::sin(tilt) * sideways).normalized();
        const double sign = uniform(rng, 0.0, 1.0) < 0.5 ? 1.0 : -1.0;
        origin = target - sign * back * approach;
        const double limit = capture_distance_m(conductor, back, beam);
        aimed.ray = ray_past(origin, target, wire_dir, uniform(rng, 0.0, 1.1) * limit,
                             uniform(rng, 0.0, 2.0 * std::numbers::pi));
        break;
      }
      case AimKind::end_cap: {
        const bool first = uniform(rng, 0.0, 1.0) < 0.5;
        const Eigen::Vector3d end = first ? points.front() : points.back();
        const Eigen::Vector3d out = first
                                        ? (points[0] - points[1]).normalized()
                                        : (points.back() - points[points.size() - 2]).normalized();
        const double limit = capture_distance_m(conductor, (end - origin).norm(), beam);
        const Eigen::Vector3d target = end + uniform(rng, 0.0, 1.2) * limit * out;
        aimed.ray = ray_past(origin, target, out, uniform(rng, 0.0, 1.0) * limit,
                             uniform(rng, 0.0, 2.0 * std::numbers::pi));
        break;
      }
      case AimKind::random: {
        const Eigen::Vector3d target = p0 + uniform(rng, 0.0, 1.0) * (p1 - p0);
        const Eigen::Vector3d sight = (target - origin).normalized();
        const Eigen::Vector3d tilt_axis = any_perpendicular(sight);
        const Eigen::Vector3d axis =
            Eigen::AngleAxisd(uniform(rng, 0.0, 2.0 * std::numbers::pi), sight) * tilt_axis;
        aimed.ray = PulseRay{
            origin,
            (Eigen::AngleAxisd(radians(uniform(rng, 0.0, 45.0)), axis) * sight).normalized()};
        break;
      }
    }
    // No origin underground or inside a capture tube: a sensor flies clear of both.
    bool clear = above_ground(scene.terrain, aimed.ray.origin_enu_m);
    for (const Conductor& c : scene.conductors) {
      for (std::size_t s = 0; s + 1 < c.points_enu_m.size() && clear; ++s) {
        const Eigen::Vector3d a = c.points_enu_m[s];
        const Eigen::Vector3d ab = c.points_enu_m[s + 1] - a;
        const double u =
            std::clamp((aimed.ray.origin_enu_m - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        clear = (aimed.ray.origin_enu_m - (a + u * ab)).norm() > 1.0;
      }
    }
    if (clear) rays.push_back(aimed);
  }
  return rays;
}

// A level, straight flight: heading fixed, constant speed along it, pitch and roll 0 unless set.
class LevelFlight final : public PoseSource {
 public:
  LevelFlight(const Eigen::Vector3d& start_enu_m, double heading_deg, double speed_mps)
      : start_(start_enu_m), heading_deg_(heading_deg), speed_(speed_mps) {}
  [[nodiscard]] Pose pose_at(double time_s) const override {
    const double h = radians(heading_deg_);
    Pose pose;
    pose.time_s = time_s;
    pose.position_enu_m = start_ + speed_ * time_s * Eigen::Vector3d(std::sin(h), std::cos(h), 0.0);
    pose.attitude.heading_deg = heading_deg_;
    return pose;
  }

 private:
  Eigen::Vector3d start_;
  double heading_deg_;
  double speed_;
};

}  // namespace owsim::test
