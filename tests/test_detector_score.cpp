// Protects the matching behind `owsim score` (evaluation/object_distance.hpp): the nearest point
// on a triangle against dense sampling of random triangles, and the distance to a conductor, a
// pole and a mesh against closed forms.
#include <gtest/gtest.h>

#include <random>

#include "evaluation/object_distance.hpp"

namespace owsim {
namespace {

TEST(ObjectDistance, NearestOnTriangleAgreesWithDenseSampling) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  const auto point = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a = point(), b = point(), c = point(), p = point();
    const Eigen::Vector3d q = nearest_on_triangle(p, a, b, c);
    double sampled = std::numeric_limits<double>::infinity();
    constexpr int kSteps = 200;
    for (int i = 0; i <= kSteps; ++i) {
      for (int j = 0; i + j <= kSteps; ++j) {
        const double s = static_cast<double>(i) / kSteps, t = static_cast<double>(j) / kSteps;
        sampled = std::min(sampled, (p - (a + s * (b - a) + t * (c - a))).norm());
      }
    }
    // q lies on the triangle (its barycentric weights are in [0, 1]) and no farther than any
    // sample.
    EXPECT_LE((p - q).norm(), sampled + 1e-9) << trial;
    EXPECT_GE((p - q).norm(), sampled - 0.2) << trial;  // the samples are ~0.1 m apart
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    EXPECT_NEAR(normal.dot(q - a), 0.0, 1e-9 * normal.norm() * 20) << trial;
  }
}

TEST(ObjectDistance, ConductorPoleAndMeshByClosedForms) {
  Scene scene;
  Conductor wire;
  wire.id = "w";
  wire.radius_m = 0.01;
  wire.points_enu_m = {{0, -100, 30}, {0, 0, 25}, {0, 100, 30}};
  scene.conductors.push_back(wire);
  Cylinder pole;
  pole.id = "p";
  pole.base_enu_m = {50, 0, 0};
  pole.radius_m = 0.5;
  pole.height_m = 20;
  scene.cylinders.push_back(pole);
  MeshObject wall;
  wall.id = "m";
  wall.mesh.vertices = {{100, -10, 0}, {100, 10, 0}, {100, 10, 10}, {100, -10, 10}};
  wall.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes.push_back(wall);
  // Straight above the wire's lowest vertex (the nearest points are on the 1:20 slopes beside
  // it); beside its middle.
  EXPECT_NEAR(distance_to_object_m(scene, 0, {0, 0, 28}), 3.0 / std::hypot(1.0, 0.05) - 0.01,
              1e-12);
  EXPECT_NEAR(distance_to_object_m(scene, 0, {4, 0, 25}), 4.0 - 0.01, 1e-12);
  // Beside the pole, above its top, inside it.
  EXPECT_NEAR(distance_to_object_m(scene, 1, {53, 0, 10}), 2.5, 1e-12);
  EXPECT_NEAR(distance_to_object_m(scene, 1, {50, 0, 26}), 6.0, 1e-12);
  EXPECT_NEAR(distance_to_object_m(scene, 1, {53.5, 0, 24}), 5.0, 1e-12);  // 3-4-5 off the rim
  EXPECT_EQ(distance_to_object_m(scene, 1, {50.2, 0, 5}), 0.0);
  // In front of the wall, beside its edge.
  EXPECT_NEAR(distance_to_object_m(scene, 2, {97, 0, 5}), 3.0, 1e-12);
  EXPECT_NEAR(distance_to_object_m(scene, 2, {100, 14, 5}), 4.0, 1e-12);
}

}  // namespace
}  // namespace owsim
