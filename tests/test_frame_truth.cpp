// Protects truth.csv's geometry (evaluation/frame_truth.hpp): "in view" is checked against brute
// force over a whole frame's rays from a hovering sensor — an object some ray points at is in
// view, the point reported for an object in view lies among the frame's rays, and its range is the
// nearest of the object's densely sampled points inside the field; the object grid finds exactly
// the objects within the timeout range; a sagging conductor's nearest points, overall and in the
// field, are those of its every segment; returns and closing speed are carried through.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <unordered_map>

#include "evaluation/frame_truth.hpp"
#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/frame_rays.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// A scene around a sensor at (0, 0, 80) looking east: wires across and along the view, poles and
// trees near and far, and a box-shaped building.
Scene random_scene(Rng& rng) {
  Scene scene;
  for (int i = 0; i < 8; ++i) {
    Conductor conductor;
    conductor.id = "w" + std::to_string(i);
    const Eigen::Vector3d a(uniform(rng, -300, 1400), uniform(rng, -900, 900),
                            uniform(rng, 0, 160));
    const Eigen::Vector3d b = a + Eigen::Vector3d(uniform(rng, -300, 300), uniform(rng, -400, 400),
                                                  uniform(rng, -20, 20));
    for (int k = 0; k <= 40; ++k) conductor.points_enu_m.push_back(a + (k / 40.0) * (b - a));
    conductor.radius_m = 0.01;
    scene.conductors.push_back(conductor);
  }
  for (int i = 0; i < 14; ++i) {
    Cylinder cylinder;
    cylinder.id = "c" + std::to_string(i);
    cylinder.surface = i % 2 == 0 ? SurfaceClass::pole : SurfaceClass::tree;
    cylinder.base_enu_m = Eigen::Vector3d(uniform(rng, -200, 1400), uniform(rng, -700, 700), 0.0);
    cylinder.radius_m = uniform(rng, 0.2, 4.0);
    cylinder.height_m = uniform(rng, 5.0, 60.0);
    scene.cylinders.push_back(cylinder);
  }
  MeshObject building;
  building.id = "barn";
  const Eigen::Vector3d corner(uniform(rng, 200, 900), uniform(rng, -300, 300), 0.0);
  for (int v = 0; v < 8; ++v) {
    building.mesh.vertices.push_back(
        corner + Eigen::Vector3d(v & 1 ? 30 : 0, v & 2 ? 20 : 0, v & 4 ? 12 : 0));
  }
  const std::array<std::array<std::uint32_t, 3>, 12> faces = {{{0, 1, 3},
                                                               {0, 3, 2},
                                                               {4, 5, 7},
                                                               {4, 7, 6},
                                                               {0, 1, 5},
                                                               {0, 5, 4},
                                                               {2, 3, 7},
                                                               {2, 7, 6},
                                                               {0, 2, 6},
                                                               {0, 6, 4},
                                                               {1, 3, 7},
                                                               {1, 7, 5}}};
  building.mesh.triangles.assign(faces.begin(), faces.end());
  scene.meshes.push_back(building);
  return scene;
}

// Points along the object's shape, about `step_m` apart (cylinders: their whole surface).
std::vector<Eigen::Vector3d> sample_object(const Scene& scene, std::size_t object, double step_m) {
  std::vector<Eigen::Vector3d> points;
  const auto along = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const int n = std::max(1, static_cast<int>((b - a).norm() / step_m));
    for (int k = 0; k <= n; ++k) points.push_back(a + (static_cast<double>(k) / n) * (b - a));
  };
  if (object < scene.conductors.size()) {
    const auto& line = scene.conductors[object].points_enu_m;
    for (std::size_t i = 1; i < line.size(); ++i) along(line[i - 1], line[i]);
  } else if (object < scene.conductors.size() + scene.cylinders.size()) {
    const Cylinder& c = scene.cylinders[object - scene.conductors.size()];
    for (int k = 0; k < 64; ++k) {
      const double angle = 2 * std::numbers::pi * k / 64;
      const Eigen::Vector3d rim =
          c.base_enu_m + c.radius_m * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
      along(rim, rim + Eigen::Vector3d(0, 0, c.height_m));
    }
  } else {
    const TriangleMesh& mesh =
        scene.meshes[object - scene.conductors.size() - scene.cylinders.size()].mesh;
    for (const auto& t : mesh.triangles) {
      for (int e = 0; e < 3; ++e) along(mesh.vertices[t[e]], mesh.vertices[t[(e + 1) % 3]]);
    }
  }
  return points;
}

class HoverFrame : public ::testing::Test {
 protected:
  void SetUp() override {
    mount.pitch_deg = -4.0;
    Pose pose;
    pose.position_enu_m = Eigen::Vector3d(0, 0, 80);
    pose.attitude = Attitude{3.0, 1.0, 90.0};  // east, a little roll and pitch
    poses = std::make_unique<FixedPose>(pose);
    sweep = frame_sweep(scan, 7, 0);
  }
  ScanParams scan;
  Mount mount;
  std::unique_ptr<FixedPose> poses;
  FrameSweep sweep;
};

TEST_F(HoverFrame, InViewAgreesWithBruteForceOverTheFramesRays) {
  Rng rng(42);
  const Scene scene = random_scene(rng);
  const FrameTruthModel model(scene, scan, mount, *poses);
  const ScanField field = frame_field(scan, sweep);
  const FieldOfView fov(field);
  const double t_mid = pulse_time_s(scan, 0, scan.pulses_per_frame() / 2);
  const SensorPlacement placement = sensor_placement(poses->pose_at(t_mid), mount, scan.model);
  const Eigen::Matrix3d src_from_enu = placement.enu_from_src.transpose();
  const auto src_of = [&](const Eigen::Vector3d& enu) {
    return Eigen::Vector3d(src_from_enu * (enu - placement.origin_enu_m));
  };

  // The frame's rays by (α, β) in 0.1° cells; with a fixed pose every ray has the placement's axes.
  struct RayAngle {
    double alpha, beta;
  };
  std::vector<RayAngle> rays;
  std::unordered_map<long, std::vector<int>> cells;
  const auto key = [](double alpha, double beta) {
    return static_cast<long>(std::floor(alpha * 10)) * 100000 +
           static_cast<long>(std::floor(beta * 10));
  };
  for (int k = 0; k < scan.pulses_per_frame(); ++k) {
    const Pulse pulse = pulse_of_frame(scan, sweep, k);
    if (pulse.reference) continue;
    // The ray the simulator traces points at this pulse's (α, β).
    const PulseRay ray = pulse_ray(pulse, *poses, mount, scan.model);
    const FieldAngles angles = field_angles(src_from_enu * ray.dir_enu);
    ASSERT_NEAR(angles.alpha_deg, pulse.alpha_deg, 1e-9);
    ASSERT_NEAR(angles.beta_deg, pulse.beta_deg, 1e-9);
    cells[key(pulse.alpha_deg, pulse.beta_deg)].push_back(static_cast<int>(rays.size()));
    rays.push_back({pulse.alpha_deg, pulse.beta_deg});
  }
  // The angular distance from (α, β) to the nearest ray, searched within ±0.5°.
  const auto nearest_ray_deg = [&](const FieldAngles& a, bool skip_edges) {
    double best = std::numeric_limits<double>::infinity();
    for (int da = -5; da <= 5; ++da) {
      for (int db = -5; db <= 5; ++db) {
        const auto found = cells.find(key(a.alpha_deg + da * 0.1, a.beta_deg + db * 0.1));
        if (found == cells.end()) continue;
        for (const int r : found->second) {
          const RayAngle& ray = rays[static_cast<std::size_t>(r)];
          if (skip_edges &&
              (ray.alpha <= field.alpha_min_deg || ray.alpha >= field.alpha_max_deg ||
               ray.beta <= field.beta_min_deg + 0.05 || ray.beta >= field.beta_max_deg - 0.05)) {
            continue;
          }
          const double d_alpha = ray.alpha - a.alpha_deg;
          const double d_beta =
              (ray.beta - a.beta_deg) * std::cos(a.alpha_deg * std::numbers::pi / 180);
          best = std::min(best, std::hypot(d_alpha, d_beta));
        }
      }
    }
    return best;
  };

  const double range_max = field.range_max_m;
  int in_view = 0, pointed_at = 0;
  for (std::uint32_t object = 0; object < named_object_count(scene); ++object) {
    const FrameTruthModel::ObjectView view = model.view_of(object, placement, fov);
    bool ray_points_at_it = false;
    double nearest_inside = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& point : sample_object(scene, object, 0.25)) {
      const Eigen::Vector3d v = src_of(point);
      if (v.norm() > range_max) continue;
      if (fov.contains(v)) nearest_inside = std::min(nearest_inside, v.norm());
      if (!ray_points_at_it && nearest_ray_deg(field_angles(v), true) < 0.02)
        ray_points_at_it = true;
    }
    SCOPED_TRACE("object " + named_object_id(scene, object));
    if (ray_points_at_it) {
      ++pointed_at;
      EXPECT_TRUE(view.in_view);
    }
    if (std::isfinite(nearest_inside)) EXPECT_TRUE(view.in_view);
    if (!view.in_view) continue;
    ++in_view;
    // The reported point is among the frame's rays (fibers ~0.34° apart, lines 0.23°).
    EXPECT_LT(nearest_ray_deg(view.angles, false), 0.45);
    EXPECT_LE(view.range_m, range_max * (1 + 1e-12));
    if (std::isfinite(nearest_inside)) {
      EXPECT_LE(view.range_m, nearest_inside + 1e-6);
      EXPECT_GE(view.range_m, nearest_inside - 0.3);  // the samples are 0.25 m apart
    }
  }
  EXPECT_GE(in_view, 6);  // the scene puts enough in front of the sensor to test something
  EXPECT_GE(pointed_at, 4);
}

TEST_F(HoverFrame, RowsHoldExactlyTheObjectsWithinTheTimeoutRangeAndTheirReturns) {
  Rng rng(7);
  Scene scene;
  for (int i = 0; i < 3000; ++i) {
    Cylinder tree;
    tree.id = "t" + std::to_string(i);
    tree.surface = SurfaceClass::tree;
    tree.base_enu_m = Eigen::Vector3d(uniform(rng, -4000, 4000), uniform(rng, -4000, 4000), 0);
    tree.radius_m = 2.0;
    tree.height_m = 15.0;
    scene.cylinders.push_back(tree);
  }
  const FrameTruthModel model(scene, scan, mount, *poses);
  const FieldOfView fov(frame_field(scan, sweep));
  const double t_mid = pulse_time_s(scan, 0, scan.pulses_per_frame() / 2);
  const SensorPlacement placement = sensor_placement(poses->pose_at(t_mid), mount, scan.model);
  // Returns on a far tree (outside the range: still a row) and three on a near one.
  std::vector<FrameTally::ObjectHit> hits;
  std::uint32_t far = 0, near = 0;
  for (std::uint32_t o = 0; o < scene.cylinders.size(); ++o) {
    const double distance = (scene.cylinders[o].base_enu_m - placement.origin_enu_m).norm();
    if (distance > 3000 && far == 0) far = o;
    if (distance < 500 && near == 0) near = o;
  }
  for (int k = 0; k < 3; ++k) hits.push_back({near, 0, 0.0, 100.0});
  hits.push_back({far, 0, 0.0, 3000.0});
  FrameTruth truth;
  model.frame_truth(0, sweep, hits, truth);
  std::vector<std::uint32_t> expected;
  for (std::uint32_t o = 0; o < scene.cylinders.size(); ++o) {
    if (o == far || model.view_of(o, placement, fov).range_m <= fov.field().range_max_m) {
      expected.push_back(o);
    }
  }
  std::vector<std::uint32_t> got;
  for (const TruthRow& row : truth.rows) {
    got.push_back(row.object);
    EXPECT_EQ(row.returns, row.object == near ? 3u : row.object == far ? 1u : 0u);
    EXPECT_NEAR(row.closing_speed_mps, 0.0, 1e-9);  // hovering
  }
  EXPECT_EQ(got, expected);
  EXPECT_GT(got.size(), 200u);
  EXPECT_NEAR(truth.time_s, t_mid, 0.0);
}

TEST_F(HoverFrame, ConductorsNearestPointsAreThoseOfTheirEverySegment) {
  // Sagging wires of 60-200 vertices (the chunks' chords and deviations matter) around the
  // sensor, seen from random poses: the nearest point overall and the nearest inside the field
  // equal a search over every segment, though the model visits only the chunks that can hold it.
  Rng rng(11);
  Scene scene;
  for (int i = 0; i < 16; ++i) {
    Conductor wire;
    wire.id = "w" + std::to_string(i);
    const Eigen::Vector3d a(uniform(rng, -900, 900), uniform(rng, -900, 900), uniform(rng, 20, 90));
    const Eigen::Vector3d b = a + Eigen::Vector3d(uniform(rng, -500, 500), uniform(rng, -500, 500),
                                                  uniform(rng, -30, 30));
    const double sag = uniform(rng, 2.0, 40.0);
    const int segments = static_cast<int>(uniform(rng, 60, 200));
    for (int k = 0; k <= segments; ++k) {
      const double u = static_cast<double>(k) / segments;
      wire.points_enu_m.push_back(a + u * (b - a) - Eigen::Vector3d(0, 0, 4 * sag * u * (1 - u)));
    }
    wire.radius_m = 0.01;
    scene.conductors.push_back(wire);
  }
  const FrameTruthModel model(scene, scan, mount, *poses);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Pose pose;
    pose.position_enu_m =
        Eigen::Vector3d(uniform(rng, -600, 600), uniform(rng, -600, 600), uniform(rng, 30, 120));
    pose.attitude = Attitude{uniform(rng, -10, 10), uniform(rng, -20, 20), uniform(rng, 0, 360)};
    const SensorPlacement placement = sensor_placement(pose, mount, scan.model);
    const FieldOfView fov(frame_field(scan, frame_sweep(scan, 7, trial)));
    const Eigen::Matrix3d src_from_enu = placement.enu_from_src.transpose();
    for (std::uint32_t object = 0; object < scene.conductors.size(); ++object) {
      const auto& points = scene.conductors[object].points_enu_m;
      double overall = std::numeric_limits<double>::infinity();
      double nearest_inside = overall;
      for (std::size_t k = 1; k < points.size(); ++k) {
        const Eigen::Vector3d a = src_from_enu * (points[k - 1] - placement.origin_enu_m);
        const Eigen::Vector3d b = src_from_enu * (points[k] - placement.origin_enu_m);
        overall = std::min(overall, (a + nearest_on_segment(a, b) * (b - a)).norm());
        if (const std::optional<double> t = fov.nearest_inside(a, b)) {
          nearest_inside = std::min(nearest_inside, (a + *t * (b - a)).norm());
        }
      }
      const FrameTruthModel::ObjectView view = model.view_of(object, placement, fov);
      SCOPED_TRACE("trial " + std::to_string(trial) + " wire " + std::to_string(object));
      EXPECT_EQ(view.in_view, std::isfinite(nearest_inside));
      EXPECT_NEAR(view.range_m, view.in_view ? nearest_inside : overall, 1e-9 * overall);
      (view.in_view ? inside : outside) += 1;
    }
  }
  EXPECT_GT(inside, 20);  // both kinds of row are compared
  EXPECT_GT(outside, 200);
}

TEST(FrameTruth, ClosingSpeedIsTheApproachRateOfTheNearestPoint) {
  // A straight flight east at 50 m/s toward a pole 1 km ahead: closing ≈ 50 m/s, and a pole
  // abeam opens at ≈ 0.
  class Straight final : public PoseSource {
   public:
    Pose pose_at(double time_s) const override {
      Pose pose;
      pose.time_s = time_s;
      pose.position_enu_m = Eigen::Vector3d(50.0 * time_s, 0, 50);
      pose.attitude.heading_deg = 90.0;
      return pose;
    }
  } straight;
  Scene scene;
  Cylinder ahead;
  ahead.id = "ahead";
  ahead.base_enu_m = Eigen::Vector3d(1000, 0, 0);
  ahead.height_m = 50.0;
  Cylinder abeam = ahead;
  abeam.id = "abeam";
  abeam.base_enu_m = Eigen::Vector3d(8.0, 300, 0);
  scene.cylinders = {ahead, abeam};
  ScanParams scan;
  const FrameTruthModel model(scene, scan, Mount{}, straight);
  FrameTruth truth;
  model.frame_truth(0, frame_sweep(scan, 1, 0), {}, truth);
  ASSERT_EQ(truth.rows.size(), 2u);
  const double t = truth.time_s;
  EXPECT_TRUE(truth.rows[0].in_view);
  EXPECT_NEAR(truth.rows[0].range_m, 1000.0 - 0.25 - 50.0 * t, 1e-6);
  EXPECT_NEAR(truth.rows[0].closing_speed_mps, 50.0, 1e-6);
  EXPECT_FALSE(truth.rows[1].in_view);  // 88° to the left
  EXPECT_NEAR(truth.rows[1].closing_speed_mps, 50.0 * (8.0 - 50.0 * t) / truth.rows[1].range_m,
              1e-3);
}

}  // namespace
}  // namespace owsim
