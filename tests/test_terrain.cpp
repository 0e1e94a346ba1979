// Protects the terrain: the height grid's sample positions (cell centres, north row first),
// bilinear heights equal to the data at the samples and exact on a plane, the extent and
// NODATA errors, the triangle mesh (two per cell, NODATA cells skipped, normals up, vertices on
// the data) and the flat plane's two triangles covering the region.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/error.hpp"
#include "geometry/terrain.hpp"

namespace owsim {
namespace {

// 4 columns × 3 rows, 10 m cells, south-west sample at (100, 200).
HeightGrid small_grid() {
  HeightGrid grid;
  grid.ncols = 4;
  grid.nrows = 3;
  grid.x_west_m = 100.0;
  grid.y_south_m = 200.0;
  grid.cellsize_m = 10.0;
  grid.heights = {1,  2,  3,  4,    // north row, n = 220
                  5,  7,  11, 13,   // n = 210
                  17, 19, 23, 29};  // south row, n = 200
  return grid;
}

Terrain grid_terrain(HeightGrid grid) {
  Terrain terrain;
  terrain.kind = TerrainKind::grid;
  terrain.grid = std::move(grid);
  return terrain;
}

double triangle_up_area(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
  return 0.5 * (b - a).cross(c - a).z();  // signed area seen from above
}

TEST(HeightGrid, BilinearEqualsTheDataAtTheSamples) {
  const HeightGrid grid = small_grid();
  EXPECT_NO_THROW(grid.validate("grid"));
  for (int row = 0; row < grid.nrows; ++row) {
    for (int col = 0; col < grid.ncols; ++col) {
      EXPECT_EQ(grid.height_at(100.0 + 10.0 * col, 220.0 - 10.0 * row), grid.sample(row, col));
    }
  }
  EXPECT_EQ(grid.height_at(100.0, 200.0), 17.0);  // south-west sample: last row, first value
  EXPECT_EQ(grid.height_at(130.0, 220.0), 4.0);   // north-east
  // Cell middle: the mean of its four samples; on an edge: linear between two.
  EXPECT_DOUBLE_EQ(grid.height_at(105.0, 205.0), (5 + 7 + 17 + 19) / 4.0);
  EXPECT_DOUBLE_EQ(grid.height_at(125.0, 210.0), 12.0);
  EXPECT_DOUBLE_EQ(grid.height_at(102.5, 200.0), 17.5);
}

TEST(HeightGrid, ReproducesAPlaneExactly) {
  HeightGrid grid;
  grid.ncols = 7;
  grid.nrows = 5;
  grid.x_west_m = -30.0;
  grid.y_south_m = 40.0;
  grid.cellsize_m = 5.0;
  const auto plane = [](double e, double n) { return 12.0 - 0.3 * e + 0.7 * n; };
  for (int row = 0; row < grid.nrows; ++row) {
    for (int col = 0; col < grid.ncols; ++col) {
      grid.heights.push_back(plane(grid.east_of_col_m(col), grid.north_of_row_m(row)));
    }
  }
  for (int i = 0; i <= 40; ++i) {
    const double e = -30.0 + 30.0 * i / 40.0, n = 40.0 + 20.0 * ((i * 7) % 41) / 40.0;
    EXPECT_NEAR(grid.height_at(e, n), plane(e, n), 1e-12) << e << ", " << n;
  }
}

TEST(HeightGrid, OutsideTheExtentAndNodataThrow) {
  HeightGrid grid = small_grid();
  EXPECT_THROW((void)grid.height_at(99.9, 205.0), Error);
  EXPECT_THROW((void)grid.height_at(130.1, 205.0), Error);
  EXPECT_THROW((void)grid.height_at(110.0, 220.1), Error);
  EXPECT_THROW((void)grid.height_at(std::nan(""), 205.0), Error);
  EXPECT_EQ(grid.height_at(130.0 + 1e-12, 220.0 + 1e-12), 4.0);  // rounding at the edge
  grid.nodata = -9999.0;
  grid.heights[5] = -9999.0;  // row 1, col 1: (110, 210)
  EXPECT_THROW((void)grid.height_at(110.0, 210.0), Error);
  EXPECT_THROW((void)grid.height_at(105.0, 205.0), Error);
  EXPECT_EQ(grid.height_at(120.0, 210.0), 11.0);  // a sample beside it: weight 0 on NODATA
  EXPECT_DOUBLE_EQ(grid.height_at(125.0, 205.0), (11 + 13 + 23 + 29) / 4.0);
  grid.heights.pop_back();
  EXPECT_THROW(grid.validate("dem.asc"), Error);
}

TEST(Terrain, GridMeshHasTwoTrianglesPerCell) {
  const Terrain terrain = grid_terrain(small_grid());
  const Eigen::AlignedBox2d everything(Eigen::Vector2d(-1e6, -1e6), Eigen::Vector2d(1e6, 1e6));
  const TriangleMesh mesh = terrain.mesh(everything);
  EXPECT_EQ(mesh.triangles.size(), 2u * 3u * 2u);
  EXPECT_EQ(mesh.vertices.size(), 12u);
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    EXPECT_GT(triangle_up_area(mesh, t), 0.0);  // counter-clockwise from above
    area += triangle_up_area(mesh, t);
  }
  EXPECT_NEAR(area, 30.0 * 20.0, 1e-9);
  for (const Eigen::Vector3d& v : mesh.vertices) {
    EXPECT_EQ(v.z(), terrain.height_at(v.x(), v.y()));
  }
  // A region over the two western cells of each row: 2 × 2 cells.
  const TriangleMesh west = terrain.mesh({Eigen::Vector2d(104, 150), Eigen::Vector2d(115, 250)});
  EXPECT_EQ(west.triangles.size(), 8u);
  EXPECT_EQ(west.vertices.size(), 9u);
  // A region wholly inside one cell, and one beside the grid.
  EXPECT_EQ(terrain.mesh({Eigen::Vector2d(111, 211), Eigen::Vector2d(112, 212)}).triangles.size(),
            2u);
  EXPECT_TRUE(terrain.mesh({Eigen::Vector2d(500, 0), Eigen::Vector2d(600, 10)}).triangles.empty());
}

TEST(Terrain, GridMeshSkipsNodataCells) {
  HeightGrid grid;
  grid.ncols = 5;
  grid.nrows = 4;
  grid.cellsize_m = 1.0;
  grid.heights.assign(20, 1.0);
  grid.nodata = -9999.0;
  grid.heights[1 * 5 + 2] = -9999.0;  // an interior sample touches 4 cells
  const Eigen::AlignedBox2d everything(Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10));
  EXPECT_EQ(grid_terrain(grid).mesh(everything).triangles.size(), 2u * (4u * 3u - 4u));
  grid.heights[0] = -9999.0;  // a corner sample touches 1 cell
  const TriangleMesh mesh = grid_terrain(grid).mesh(everything);
  EXPECT_EQ(mesh.triangles.size(), 2u * (4u * 3u - 5u));
  for (const Eigen::Vector3d& v : mesh.vertices) EXPECT_EQ(v.z(), 1.0);  // no NODATA vertex
}

TEST(Terrain, FlatAndNone) {
  Terrain flat;
  flat.flat_u_m = 450.0;
  EXPECT_EQ(flat.kind, TerrainKind::flat);
  EXPECT_DOUBLE_EQ(flat.reflectivity, 0.2);
  EXPECT_EQ(flat.height_at(-1e5, 3e4), 450.0);
  const Eigen::AlignedBox2d region(Eigen::Vector2d(-10, 5), Eigen::Vector2d(20, 50));
  const TriangleMesh mesh = flat.mesh(region);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    EXPECT_GT(triangle_up_area(mesh, t), 0.0);
    area += triangle_up_area(mesh, t);
  }
  EXPECT_NEAR(area, 30.0 * 45.0, 1e-9);  // the two triangles cover the region exactly
  Eigen::AlignedBox2d covered;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    EXPECT_EQ(v.z(), 450.0);
    covered.extend(Eigen::Vector2d(v.x(), v.y()));
  }
  EXPECT_TRUE(covered.isApprox(region));
  EXPECT_TRUE(flat.mesh(Eigen::AlignedBox2d()).triangles.empty());  // empty region

  Terrain none;
  none.kind = TerrainKind::none;
  EXPECT_EQ(none.height_at(12.0, 34.0), 0.0);
  EXPECT_TRUE(none.mesh(region).triangles.empty());
}

}  // namespace
}  // namespace owsim
