// Protects the 3D span of SENSOR-SPEC §6 on sloped terrain: attachment points at terrain + H
// under each support, the lowest point S above the lower support's ground, conductors ending at
// the pole tops, pole bases on the terrain, the vertical plane of each conductor, and the error
// keys of a bad span.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/catenary.hpp"
#include "geometry/error.hpp"
#include "geometry/span.hpp"

namespace owsim {
namespace {

double plane_u(double e, double n) { return 100.0 + 0.05 * e + 0.02 * n; }

// A tilted plane sampled on a 10 m grid: bilinear interpolation reproduces it exactly.
Terrain sloped_terrain() {
  Terrain terrain;
  terrain.kind = TerrainKind::grid;
  HeightGrid& grid = terrain.grid;
  grid.ncols = 51;
  grid.nrows = 41;
  grid.x_west_m = -100.0;
  grid.y_south_m = -100.0;
  grid.cellsize_m = 10.0;
  for (int row = 0; row < grid.nrows; ++row) {
    for (int col = 0; col < grid.ncols; ++col) {
      grid.heights.push_back(plane_u(grid.east_of_col_m(col), grid.north_of_row_m(row)));
    }
  }
  return terrain;
}

SpanSpec sloped_span() {
  SpanSpec spec;
  spec.id = "hill";
  spec.from_en = {10.0, 20.0};
  spec.to_en = {310.0, 170.0};
  spec.support_height_1_m = 30.0;
  spec.support_height_2_m = 25.0;
  spec.lowest_point_m = 12.0;
  return spec;
}

void expect_vectors_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected,
                         double tol) {
  EXPECT_LT((actual - expected).norm(), tol)
      << actual.transpose() << " vs " << expected.transpose();
}

double lowest_u(const Conductor& conductor) {
  double lowest = conductor.points_enu_m.front().z();
  for (const Eigen::Vector3d& p : conductor.points_enu_m) lowest = std::min(lowest, p.z());
  return lowest;
}

std::string error_of(const SpanSpec& spec, const Terrain& terrain, std::string_view where) {
  try {
    (void)build_span(spec, terrain, where);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(Span, SupportsStandOnSlopedTerrain) {
  const Terrain terrain = sloped_terrain();
  const SpanObjects span = build_span(sloped_span(), terrain);
  const double ground_1 = plane_u(10, 20), ground_2 = plane_u(310, 170);  // 100.9, 118.9
  ASSERT_EQ(span.conductors.size(), 1u);
  const Conductor& wire = span.conductors[0];
  EXPECT_EQ(wire.id, "hill/1");
  EXPECT_DOUBLE_EQ(wire.radius_m, 0.010);
  EXPECT_DOUBLE_EQ(wire.reflectivity, 0.4);
  expect_vectors_near(wire.points_enu_m.front(), {10, 20, ground_1 + 30.0}, 1e-9);
  expect_vectors_near(wire.points_enu_m.back(), {310, 170, ground_2 + 25.0}, 1e-9);
  // S above the lower support's ground, reached within the 1 mm sampling.
  const double lowest = lowest_u(wire);
  EXPECT_GE(lowest, ground_1 + 12.0 - 1e-9);
  EXPECT_LT(lowest, ground_1 + 12.0 + 1e-3);
  // Every vertex lies in the vertical plane from → to and on the catenary.
  const Catenary catenary = Catenary::solve(
      {std::hypot(300.0, 150.0), ground_1 + 30.0, ground_2 + 25.0, ground_1 + 12.0});
  const Eigen::Vector2d forward = Eigen::Vector2d(300, 150).normalized();
  for (const Eigen::Vector3d& p : wire.points_enu_m) {
    const Eigen::Vector2d offset = p.head<2>() - Eigen::Vector2d(10, 20);
    EXPECT_NEAR(offset.x() * forward.y() - offset.y() * forward.x(), 0.0, 1e-9);
    EXPECT_NEAR(p.z(), catenary.height_at(offset.dot(forward)), 1e-9);
  }
  // A modest number of vertices for a 335 m span sampled to 1 mm.
  EXPECT_GT(wire.points_enu_m.size(), 50u);
  EXPECT_LT(wire.points_enu_m.size(), 500u);

  ASSERT_EQ(span.poles.size(), 2u);
  EXPECT_EQ(span.poles[0].id, "hill/pole-1");
  EXPECT_EQ(span.poles[1].id, "hill/pole-2");
  for (const Cylinder& pole : span.poles) {
    EXPECT_EQ(pole.surface, SurfaceClass::pole);
    EXPECT_DOUBLE_EQ(pole.radius_m, 0.25);
    EXPECT_DOUBLE_EQ(pole.reflectivity, 0.3);
    EXPECT_NEAR(pole.base_enu_m.z(), plane_u(pole.base_enu_m.x(), pole.base_enu_m.y()), 1e-9);
  }
  // The wire ends at the pole tops.
  const auto top = [](const Cylinder& pole) {
    return Eigen::Vector3d(pole.base_enu_m + Eigen::Vector3d(0, 0, pole.height_m));
  };
  expect_vectors_near(top(span.poles[0]), wire.points_enu_m.front(), 1e-9);
  expect_vectors_near(top(span.poles[1]), wire.points_enu_m.back(), 1e-9);
}

TEST(Span, SeptTowerOnSlopedTerrain) {
  const Terrain terrain = sloped_terrain();
  SpanSpec spec = sloped_span();
  spec.offsets = conductor_offsets(LayoutKind::sept);
  const SpanObjects span = build_span(spec, terrain);
  ASSERT_EQ(span.conductors.size(), 7u);
  const double ground_1 = plane_u(10, 20), ground_2 = plane_u(310, 170);
  const Eigen::Vector2d right = Eigen::Vector2d(150, -300).normalized();
  for (std::size_t i = 0; i < 7; ++i) {
    const ConductorOffset offset = spec.offsets[i];
    const Conductor& wire = span.conductors[i];
    const Eigen::Vector2d start = Eigen::Vector2d(10, 20) + offset.lateral_m * right;
    const Eigen::Vector2d end = Eigen::Vector2d(310, 170) + offset.lateral_m * right;
    expect_vectors_near(wire.points_enu_m.front(),
                        {start.x(), start.y(), ground_1 + 30.0 + offset.vertical_m}, 1e-9);
    expect_vectors_near(wire.points_enu_m.back(),
                        {end.x(), end.y(), ground_2 + 25.0 + offset.vertical_m}, 1e-9);
    EXPECT_NEAR(lowest_u(wire), ground_1 + 12.0 + offset.vertical_m, 1e-3);
  }
  // The tower's top is the earth wire: the poles reach the support heights.
  EXPECT_DOUBLE_EQ(span.poles[0].height_m, 30.0);
  EXPECT_DOUBLE_EQ(span.poles[1].height_m, 25.0);
}

TEST(Span, PolesReachARaisedConductorAndCanBeOmitted) {
  const Terrain terrain = sloped_terrain();
  SpanSpec spec = sloped_span();
  spec.offsets = {{-3.0, 2.0}, {3.0, -1.0}};
  const SpanObjects span = build_span(spec, terrain);
  EXPECT_DOUBLE_EQ(span.poles[0].height_m, 32.0);
  EXPECT_NEAR(span.conductors[0].points_enu_m.front().z(),
              span.poles[0].base_enu_m.z() + span.poles[0].height_m, 1e-9);
  spec.support_poles = false;
  EXPECT_TRUE(build_span(spec, terrain).poles.empty());
}

TEST(Span, BadFieldsNameTheirKey) {
  const Terrain terrain = sloped_terrain();
  const std::string where = "scene.spans[3]";
  const auto expect_key = [&](const SpanSpec& spec, const std::string& key) {
    const std::string message = error_of(spec, terrain, where);
    EXPECT_EQ(message.rfind(where + "." + key + ": ", 0), 0u) << message;
  };
  SpanSpec spec = sloped_span();
  spec.lowest_point_m = 26.0;  // above support 2 (25 m)
  expect_key(spec, "lowest_point_m");
  spec = sloped_span();
  spec.lowest_point_m = -1.0;
  expect_key(spec, "lowest_point_m");
  spec = sloped_span();
  spec.offsets = conductor_offsets(LayoutKind::sept);  // 12 m − 11 m fine; 5 m − 11 m not
  spec.lowest_point_m = 5.0;
  expect_key(spec, "lowest_point_m");
  spec = sloped_span();
  spec.to_en = spec.from_en;
  expect_key(spec, "to");
  spec = sloped_span();
  spec.from_en = {1000.0, 0.0};  // off the grid
  expect_key(spec, "from");
  spec = sloped_span();
  spec.support_height_2_m = std::nan("");
  expect_key(spec, "support_heights_m");
  spec = sloped_span();
  spec.conductor_diameter_m = -0.02;
  expect_key(spec, "conductor.diameter_mm");
  EXPECT_NE(error_of(spec, terrain, where).find("-20 mm"), std::string::npos);
  spec = sloped_span();
  spec.conductor_reflectivity = 1.5;
  expect_key(spec, "conductor.reflectivity");
  spec = sloped_span();
  spec.pole_diameter_m = 0.0;
  expect_key(spec, "supports.diameter_m");
  spec.support_poles = false;  // ignored without poles
  EXPECT_EQ(error_of(spec, terrain, where), "no error");
  spec = sloped_span();
  spec.offsets.clear();
  expect_key(spec, "layout");
  spec = sloped_span();
  spec.id.clear();
  expect_key(spec, "id");
  // Without a prefix the key stands alone.
  spec = sloped_span();
  spec.lowest_point_m = 40.0;
  EXPECT_EQ(error_of(spec, terrain, "").rfind("lowest_point_m: ", 0), 0u);
}

TEST(Span, EqualRelativeHeightsOnASlopeStillSag) {
  // S equal to both support heights above their own ground is solvable on a slope: the vertex
  // sits at the lower support.
  const Terrain terrain = sloped_terrain();
  SpanSpec spec = sloped_span();
  spec.support_height_1_m = 20.0;
  spec.support_height_2_m = 20.0;
  spec.lowest_point_m = 20.0;
  const SpanObjects span = build_span(spec, terrain);
  EXPECT_NEAR(lowest_u(span.conductors[0]), plane_u(10, 20) + 20.0, 1e-9);
  // On flat ground the same numbers give no sag at all.
  EXPECT_EQ(error_of(spec, Terrain{}, "s").rfind("s.lowest_point_m: ", 0), 0u);
}

}  // namespace
}  // namespace owsim
