// Protects build_scene (io/scenario/scene_builder.hpp): a scenario's spans become one object per
// conductor
// ("<span>/<n>") plus support poles on the terrain, poles and trees keep their placement and
// class, the forest follows the scenario seed, and a bad scene names the file and key.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "geometry/error.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"

namespace owsim {
namespace {

constexpr const char* kScenario = R"(name: builder
seed: 7
origin: {lat: 48.6881, lon: 10.8447, h: 450}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: -500, n: 0, u: 100}, {e: 500, n: 0, u: 100}]
scene:
  terrain: {flat_u: 12}
  spans:
    - id: tri-line
      from: {e: 0, n: -150}
      to: {e: 0, n: 150}
      support_heights_m: [40, 36]
      lowest_point_m: 25
      layout: tri
      conductor: {diameter_mm: 18, reflectivity: 0.45}
      supports: {kind: pole, diameter_m: 0.8, reflectivity: 0.25}
    - id: bare
      from: {e: 100, n: -100}
      to: {e: 300, n: -100}
      layout: [[0, 0], [0, -3]]
      supports: {kind: none}
  poles:
    - {id: mast, at: {e: 50, n: 50}, height_m: 25, diameter_m: 0.4}
  trees:
    - {id: oak, at: {e: -40, n: 20, u: 15}, height_m: 12, diameter_m: 6, reflectivity: 0.25}
  forest: {count: 25, area: {e: [-200, 200], n: [300, 400]}, height_m: [8, 20], diameter_m: [2, 5]}
)";

const Cylinder& find_cylinder(const Scene& scene, const std::string& id) {
  const auto found = std::find_if(scene.cylinders.begin(), scene.cylinders.end(),
                                  [&](const Cylinder& c) { return c.id == id; });
  if (found == scene.cylinders.end()) throw Error("no cylinder " + id);
  return *found;
}

TEST(SceneBuilder, SpansPolesTreesAndForest) {
  const Scenario scenario = load_scenario_text(kScenario, "/s/builder.yaml");
  const Scene scene = build_scene(scenario);

  // Conductors: three of the tri span, two of the custom one, in span then layout order.
  ASSERT_EQ(scene.conductors.size(), 5u);
  const std::vector<std::string> ids = {"tri-line/1", "tri-line/2", "tri-line/3", "bare/1",
                                        "bare/2"};
  for (std::size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(scene.conductors[i].id, ids[i]);
  for (std::size_t i = 0; i < 3; ++i) {
    const Conductor& wire = scene.conductors[i];
    EXPECT_DOUBLE_EQ(wire.radius_m, 0.009);
    EXPECT_DOUBLE_EQ(wire.reflectivity, 0.45);
    // Ends at the support heights above the flat terrain (u = 12), lowest point S above it.
    EXPECT_NEAR(wire.points_enu_m.front().z(), 12.0 + 40.0, 1e-3);
    EXPECT_NEAR(wire.points_enu_m.back().z(), 12.0 + 36.0, 1e-3);
    double lowest = wire.points_enu_m.front().z();
    for (const Eigen::Vector3d& p : wire.points_enu_m) lowest = std::min(lowest, p.z());
    EXPECT_NEAR(lowest, 12.0 + 25.0, 0.01);
  }
  // tri: lateral −4, 0, 4 m to the right of from → to (north), i.e. east is +.
  EXPECT_NEAR(scene.conductors[0].points_enu_m.front().x(), -4.0, 1e-9);
  EXPECT_NEAR(scene.conductors[2].points_enu_m.front().x(), 4.0, 1e-9);
  EXPECT_NEAR(scene.conductors[4].points_enu_m.front().z(), 12.0 + 30.0 - 3.0, 1e-3);

  // Cylinders: two support poles of tri-line only, then mast, oak, 25 forest trees.
  ASSERT_EQ(scene.cylinders.size(), 2u + 1u + 1u + 25u);
  const Cylinder& pole1 = find_cylinder(scene, "tri-line/pole-1");
  EXPECT_EQ(pole1.surface, SurfaceClass::pole);
  EXPECT_EQ(pole1.base_enu_m, Eigen::Vector3d(0, -150, 12));
  EXPECT_DOUBLE_EQ(pole1.radius_m, 0.4);
  EXPECT_DOUBLE_EQ(pole1.reflectivity, 0.25);
  EXPECT_EQ(find_cylinder(scene, "tri-line/pole-2").base_enu_m, Eigen::Vector3d(0, 150, 12));
  EXPECT_THROW((void)find_cylinder(scene, "bare/pole-1"), Error);

  const Cylinder& mast = find_cylinder(scene, "mast");
  EXPECT_EQ(mast.surface, SurfaceClass::pole);
  EXPECT_EQ(mast.base_enu_m, Eigen::Vector3d(50, 50, 12));  // on the terrain
  EXPECT_DOUBLE_EQ(mast.height_m, 25.0);
  const Cylinder& oak = find_cylinder(scene, "oak");
  EXPECT_EQ(oak.surface, SurfaceClass::tree);
  EXPECT_EQ(oak.base_enu_m, Eigen::Vector3d(-40, 20, 15));  // u as given
  EXPECT_DOUBLE_EQ(oak.radius_m, 3.0);

  std::set<std::string> unique;
  for (const Cylinder& c : scene.cylinders) EXPECT_TRUE(unique.insert(c.id).second) << c.id;
  for (int i = 0; i < 25; ++i) {
    const Cylinder& tree = find_cylinder(scene, "forest/" + std::to_string(i));
    EXPECT_EQ(tree.surface, SurfaceClass::tree);
    EXPECT_GE(tree.base_enu_m.x(), -200.0);
    EXPECT_LE(tree.base_enu_m.x(), 200.0);
    EXPECT_GE(tree.base_enu_m.y(), 300.0);
    EXPECT_LE(tree.base_enu_m.y(), 400.0);
    EXPECT_DOUBLE_EQ(tree.base_enu_m.z(), 12.0);
    EXPECT_GE(tree.height_m, 8.0);
    EXPECT_LE(tree.height_m, 20.0);
    EXPECT_DOUBLE_EQ(tree.reflectivity, 0.2);
  }
  EXPECT_EQ(scene.terrain.kind, TerrainKind::flat);
  EXPECT_DOUBLE_EQ(scene.terrain.flat_u_m, 12.0);
}

TEST(SceneBuilder, ForestFollowsTheSeed) {
  Scenario scenario = load_scenario_text(kScenario, "/s/builder.yaml");
  const Scene first = build_scene(scenario);
  const Scene again = build_scene(scenario);
  const Cylinder& a = find_cylinder(first, "forest/3");
  EXPECT_EQ(a.base_enu_m, find_cylinder(again, "forest/3").base_enu_m);
  EXPECT_EQ(a.radius_m, find_cylinder(again, "forest/3").radius_m);
  scenario.seed = 8;
  const Scene other = build_scene(scenario);
  EXPECT_NE(a.base_enu_m, find_cylinder(other, "forest/3").base_enu_m);
  // The same forest as generate_forest with the scenario's seed.
  const std::vector<Cylinder> direct =
      generate_forest(*scenario.scene.forest, 7, scenario.scene.terrain);
  EXPECT_EQ(direct[3].base_enu_m, a.base_enu_m);
}

TEST(SceneBuilder, EmptySceneHasOnlyTerrain) {
  Scenario scenario;
  const Scene scene = build_scene(scenario);
  EXPECT_TRUE(scene.conductors.empty());
  EXPECT_TRUE(scene.cylinders.empty());
  EXPECT_EQ(scene.terrain.kind, TerrainKind::flat);
}

TEST(SceneBuilder, BadSceneInCodeNamesFileAndKey) {
  Scenario scenario;
  scenario.path = "/s/code.yaml";
  SpanSpec span;
  span.id = "x";
  span.to_en = {100.0, 0.0};
  span.lowest_point_m = 50.0;  // above its 30 m supports
  scenario.scene.spans.push_back(span);
  try {
    (void)build_scene(scenario);
    ADD_FAILURE() << "built";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("/s/code.yaml: scene.spans[0].lowest_point_m: ", 0),
              0u)
        << error.what();
  }
}

}  // namespace
}  // namespace owsim
