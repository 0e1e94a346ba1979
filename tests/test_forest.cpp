// Protects the forest generator: count, every tree inside its area and ranges and on the
// terrain, the keyed draw of tree i (seed, 0, i, forest_layout), determinism per seed, prefix
// stability when trees are added, different seeds giving different forests, and error keys.
#include <gtest/gtest.h>

#include <string>

#include "geometry/error.hpp"
#include "geometry/forest.hpp"
#include "geometry/keyed_random.hpp"

namespace owsim {
namespace {

ForestSpec spec_of(int count) {
  ForestSpec spec;
  spec.count = count;
  spec.e_range = {100.0, 300.0};
  spec.n_range = {-50.0, 50.0};
  spec.height_min_m = 8.0;
  spec.height_max_m = 25.0;
  spec.diameter_min_m = 2.0;
  spec.diameter_max_m = 8.0;
  return spec;
}

Terrain flat_at(double u) {
  Terrain terrain;
  terrain.flat_u_m = u;
  return terrain;
}

bool same_tree(const Cylinder& a, const Cylinder& b) {
  return a.id == b.id && a.base_enu_m == b.base_enu_m && a.radius_m == b.radius_m &&
         a.height_m == b.height_m && a.reflectivity == b.reflectivity && a.surface == b.surface;
}

std::string error_of(const ForestSpec& spec, const Terrain& terrain) {
  try {
    (void)generate_forest(spec, 42, terrain);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(Forest, TreesStayInsideTheirAreaAndRanges) {
  const std::vector<Cylinder> trees = generate_forest(spec_of(500), 42, flat_at(3.0));
  ASSERT_EQ(trees.size(), 500u);
  double mean_e = 0.0;
  for (std::size_t i = 0; i < trees.size(); ++i) {
    const Cylinder& tree = trees[i];
    EXPECT_EQ(tree.id, "forest/" + std::to_string(i));
    EXPECT_EQ(tree.surface, SurfaceClass::tree);
    EXPECT_DOUBLE_EQ(tree.reflectivity, 0.2);
    EXPECT_GE(tree.base_enu_m.x(), 100.0);
    EXPECT_LT(tree.base_enu_m.x(), 300.0);
    EXPECT_GE(tree.base_enu_m.y(), -50.0);
    EXPECT_LT(tree.base_enu_m.y(), 50.0);
    EXPECT_EQ(tree.base_enu_m.z(), 3.0);
    EXPECT_GE(tree.height_m, 8.0);
    EXPECT_LT(tree.height_m, 25.0);
    EXPECT_GE(tree.radius_m, 1.0);
    EXPECT_LT(tree.radius_m, 4.0);
    mean_e += tree.base_enu_m.x() / 500.0;
  }
  EXPECT_NEAR(mean_e, 200.0, 10.0);  // uniform: σ of the mean ≈ 2.6 m
}

TEST(Forest, TreeIComesFromItsOwnKeyedBlock) {
  const std::vector<Cylinder> trees = generate_forest(spec_of(8), 7, flat_at(0.0));
  const PhiloxBlock block = random_block({7, 0, 5, RandomPurpose::forest_layout});
  EXPECT_DOUBLE_EQ(trees[5].base_enu_m.x(), 100.0 + 200.0 * block[0] * 0x1.0p-32);
  EXPECT_DOUBLE_EQ(trees[5].base_enu_m.y(), -50.0 + 100.0 * block[1] * 0x1.0p-32);
  EXPECT_DOUBLE_EQ(trees[5].height_m, 8.0 + 17.0 * block[2] * 0x1.0p-32);
  EXPECT_DOUBLE_EQ(trees[5].radius_m, 0.5 * (2.0 + 6.0 * block[3] * 0x1.0p-32));
}

TEST(Forest, DeterministicAndPrefixStable) {
  const std::vector<Cylinder> a = generate_forest(spec_of(200), 42, flat_at(0.0));
  const std::vector<Cylinder> b = generate_forest(spec_of(200), 42, flat_at(0.0));
  const std::vector<Cylinder> prefix = generate_forest(spec_of(50), 42, flat_at(0.0));
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(same_tree(a[i], b[i])) << i;
  for (std::size_t i = 0; i < prefix.size(); ++i) EXPECT_TRUE(same_tree(a[i], prefix[i])) << i;
  const std::vector<Cylinder> other = generate_forest(spec_of(200), 43, flat_at(0.0));
  int moved = 0;
  for (std::size_t i = 0; i < a.size(); ++i) moved += a[i].base_enu_m != other[i].base_enu_m;
  EXPECT_EQ(moved, 200);
  EXPECT_TRUE(generate_forest(spec_of(0), 42, flat_at(0.0)).empty());
}

TEST(Forest, TreesStandOnGridTerrain) {
  Terrain terrain;
  terrain.kind = TerrainKind::grid;
  terrain.grid = {.ncols = 3,
                  .nrows = 3,
                  .x_west_m = 0.0,
                  .y_south_m = -100.0,
                  .cellsize_m = 200.0,
                  .heights = {10, 20, 30, 40, 50, 60, 70, 80, 90}};
  for (const Cylinder& tree : generate_forest(spec_of(50), 42, terrain)) {
    EXPECT_DOUBLE_EQ(tree.base_enu_m.z(),
                     terrain.height_at(tree.base_enu_m.x(), tree.base_enu_m.y()));
  }
  ForestSpec off_grid = spec_of(50);
  off_grid.e_range = {500.0, 600.0};  // east of the grid
  EXPECT_EQ(error_of(off_grid, terrain).rfind("scene.forest.area: tree 0: ", 0), 0u)
      << error_of(off_grid, terrain);
}

TEST(Forest, BadSpecsNameTheirKey) {
  const Terrain flat = flat_at(0.0);
  ForestSpec spec = spec_of(-1);
  EXPECT_EQ(error_of(spec, flat).rfind("scene.forest.count: ", 0), 0u);
  spec = spec_of(5);
  spec.e_range = {300.0, 100.0};
  EXPECT_EQ(error_of(spec, flat).rfind("scene.forest.area.e: ", 0), 0u);
  spec = spec_of(5);
  spec.n_range = {0.0, std::nan("")};
  EXPECT_EQ(error_of(spec, flat).rfind("scene.forest.area.n: ", 0), 0u);
  spec = spec_of(5);
  spec.height_min_m = 0.0;
  EXPECT_EQ(error_of(spec, flat).rfind("scene.forest.height_m: ", 0), 0u);
  spec = spec_of(5);
  spec.diameter_max_m = 1.0;
  EXPECT_EQ(error_of(spec, flat).rfind("scene.forest.diameter_m: ", 0), 0u);
  spec = spec_of(5);
  spec.reflectivity = -0.1;
  EXPECT_EQ(error_of(spec, flat).rfind("scene.forest.reflectivity: ", 0), 0u);
  spec = spec_of(5);
  spec.height_min_m = spec.height_max_m = 12.0;  // a single height is fine
  EXPECT_EQ(error_of(spec, flat), "no error");
}

}  // namespace
}  // namespace owsim
