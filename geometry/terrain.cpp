#include "geometry/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/error.hpp"

namespace owsim {
namespace {

TriangleMesh flat_mesh(const Eigen::AlignedBox2d& region, double u_m) {
  const Eigen::Vector2d lo = region.min(), hi = region.max();
  TriangleMesh mesh;
  mesh.vertices = {
      {lo.x(), lo.y(), u_m}, {hi.x(), lo.y(), u_m}, {hi.x(), hi.y(), u_m}, {lo.x(), hi.y(), u_m}};
  mesh.triangles = {{{0, 1, 2}}, {{0, 2, 3}}};
  return mesh;
}

// Range of lattice cells [first, last] along one axis whose extent overlaps [lo, hi] (cells
// measured from the first sample); false when none does.
bool overlapping_cells(double lo_cells, double hi_cells, int samples, int& first, int& last) {
  const int cells = samples - 1;
  if (hi_cells < 0.0 || lo_cells > cells) return false;
  first = std::clamp(static_cast<int>(std::floor(lo_cells)), 0, cells - 1);
  last = std::clamp(static_cast<int>(std::ceil(hi_cells)) - 1, first, cells - 1);
  return true;
}

TriangleMesh grid_mesh(const Eigen::AlignedBox2d& region, const HeightGrid& grid) {
  TriangleMesh mesh;
  int col_first = 0, col_last = 0, srow_first = 0, srow_last = 0;  // srow: rows from the south
  const double cs = grid.cellsize_m;
  if (!overlapping_cells((region.min().x() - grid.x_west_m) / cs,
                         (region.max().x() - grid.x_west_m) / cs, grid.ncols, col_first,
                         col_last) ||
      !overlapping_cells((region.min().y() - grid.y_south_m) / cs,
                         (region.max().y() - grid.y_south_m) / cs, grid.nrows, srow_first,
                         srow_last)) {
    return mesh;
  }
  const int node_cols = col_last - col_first + 2, node_rows = srow_last - srow_first + 2;
  if (static_cast<double>(node_cols) * node_rows >
      static_cast<double>(std::numeric_limits<std::uint32_t>::max())) {
    throw Error("terrain grid: the mesh of the region would exceed 2^32 vertices");
  }
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> vertex_of_node(
      static_cast<std::size_t>(node_cols) * static_cast<std::size_t>(node_rows), kUnused);
  const auto vertex = [&](int srow, int col) {
    const auto slot = static_cast<std::size_t>(srow - srow_first) * node_cols + (col - col_first);
    if (vertex_of_node[slot] == kUnused) {
      const int row = grid.nrows - 1 - srow;
      vertex_of_node[slot] = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.emplace_back(grid.east_of_col_m(col), grid.north_of_row_m(row),
                                 grid.sample(row, col));
    }
    return vertex_of_node[slot];
  };
  for (int srow = srow_first; srow <= srow_last; ++srow) {
    for (int col = col_first; col <= col_last; ++col) {
      const int south = grid.nrows - 1 - srow, north = south - 1;
      if (grid.is_nodata(grid.sample(south, col)) || grid.is_nodata(grid.sample(south, col + 1)) ||
          grid.is_nodata(grid.sample(north, col)) || grid.is_nodata(grid.sample(north, col + 1))) {
        continue;
      }
      const std::uint32_t sw = vertex(srow, col), se = vertex(srow, col + 1),
                          nw = vertex(srow + 1, col), ne = vertex(srow + 1, col + 1);
      mesh.triangles.push_back({sw, se, ne});
      mesh.triangles.push_back({sw, ne, nw});
    }
  }
  return mesh;
}

}  // namespace

double Terrain::height_at(double e_m, double n_m) const {
  switch (kind) {
    case TerrainKind::none:
      return 0.0;
    case TerrainKind::flat:
      return flat_u_m;
    case TerrainKind::grid:
      return grid.height_at(e_m, n_m);
    case TerrainKind::dem:
      return dem->height_at(e_m, n_m);
  }
  return 0.0;
}

TriangleMesh Terrain::mesh(const Eigen::AlignedBox2d& region) const {
  if (region.isEmpty()) return {};
  switch (kind) {
    case TerrainKind::none:
      return {};
    case TerrainKind::flat:
      return flat_mesh(region, flat_u_m);
    case TerrainKind::grid:
      return grid_mesh(region, grid);
    case TerrainKind::dem:
      return dem->mesh(region);
  }
  return {};
}

}  // namespace owsim
