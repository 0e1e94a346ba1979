#include "engine/terrain_grids.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {
namespace {

// The cell a grid's u or v (uniform over the whole grid) falls in, and the fraction across it.
struct CellCoordinate {
  int cell = 0;
  double fraction = 0.0;
};

CellCoordinate cell_coordinate(float uv, int cells) {
  const double scaled = static_cast<double>(uv) * cells;
  const int cell = std::clamp(static_cast<int>(std::floor(scaled)), 0, cells - 1);
  return {cell, scaled - cell};
}

std::optional<TriangleHit> triangle_hit(const std::array<Eigen::Vector3d, 3>& triangle,
                                        const PulseRay& ray) {
  return intersect_triangle(ray.origin_enu_m, ray.dir_enu, triangle[0], triangle[1], triangle[2],
                            0.0, std::numeric_limits<double>::infinity());
}

// Where the tiles along one side of `cells` cells begin, and its end: kTileCells apart, the last
// tile taking a remainder of one cell (a grid is at least 2 × 2 cells, see the header).
std::vector<int> tile_starts(int cells) {
  std::vector<int> starts;
  for (int start = 0; start < cells; start += TerrainGrids::kTileCells) starts.push_back(start);
  if (starts.size() > 1 && cells - starts.back() < 2) starts.pop_back();
  starts.push_back(cells);
  return starts;
}

}  // namespace

TerrainGrids::TerrainGrids(const PostLattice& lattice, const Eigen::AlignedBox2d& region)
    : lattice_(&lattice) {
  if (region.isEmpty()) return;
  if (lattice.posts.size() > std::numeric_limits<unsigned>::max()) {
    throw Error("DEM: more than 2^32 posts in reach, more than Embree can index");
  }
  const std::vector<int> row_starts = tile_starts(lattice.nrows - 1);
  const std::vector<int> col_starts = tile_starts(lattice.ncols - 1);
  for (std::size_t i = 0; i + 1 < row_starts.size(); ++i) {
    const int r0 = row_starts[i], r1 = row_starts[i + 1];
    for (std::size_t j = 0; j + 1 < col_starts.size(); ++j) {
      const int c0 = col_starts[j], c1 = col_starts[j + 1];
      Eigen::AlignedBox2d box;
      bool holes = false;
      for (int r = r0; r <= r1; ++r) {
        for (int c = c0; c <= c1; ++c) {
          box.extend(lattice.post(r, c).head<2>());
          if (r < r1 && c < c1 && !lattice.cell_has_heights(r, c)) holes = true;
        }
      }
      if (!box.intersects(region)) continue;
      if (!holes && r1 - r0 >= 2 && c1 - c0 >= 2) {
        grids_.push_back(RTCGrid{
            static_cast<unsigned>(lattice.index(r0, c0)), static_cast<unsigned>(lattice.ncols),
            static_cast<unsigned short>(c1 - c0 + 1), static_cast<unsigned short>(r1 - r0 + 1)});
        continue;
      }
      for (int r = r0; r < r1; ++r) {
        for (int c = c0; c < c1; ++c) {
          if (!lattice.cell_has_heights(r, c)) continue;
          for (int which = 0; which < 2; ++which) {
            const std::array<Eigen::Vector3d, 3> triangle = lattice.cell_triangle(r, c, which);
            const auto first = static_cast<std::uint32_t>(patches_.vertices.size());
            patches_.vertices.insert(patches_.vertices.end(), triangle.begin(), triangle.end());
            patches_.triangles.push_back({first, first + 1, first + 2});
          }
        }
      }
    }
  }
}

RTCGeometry TerrainGrids::grid_geometry(RTCDevice device) const {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_GRID);
  const std::vector<Eigen::Vector3d>& posts = lattice_->posts;
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), posts.size()));
  for (std::size_t p = 0; p < posts.size(); ++p) {
    for (int axis = 0; axis < 3; ++axis) {
      vertices[3 * p + static_cast<std::size_t>(axis)] = static_cast<float>(posts[p][axis]);
    }
  }
  auto* grids = static_cast<RTCGrid*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(RTCGrid), grids_.size()));
  std::copy(grids_.begin(), grids_.end(), grids);
  rtcCommitGeometry(geometry);
  return geometry;
}

TriangleHit TerrainGrids::exact_grid_hit(unsigned prim_id, float u, float v,
                                         const PulseRay& ray) const {
  const RTCGrid& grid = grids_[prim_id];
  const PostLattice& lattice = *lattice_;
  const auto stride = static_cast<unsigned>(lattice.ncols);
  const CellCoordinate across = cell_coordinate(u, grid.width - 1);
  const CellCoordinate down = cell_coordinate(v, grid.height - 1);
  const int row = static_cast<int>(grid.startVertexID / stride) + down.cell;
  const int col = static_cast<int>(grid.startVertexID % stride) + across.cell;
  // Embree's quad (x, y): triangle (x, y), (x + 1, y), (x, y + 1) where the fractions sum to at
  // most 1 — the lattice's triangle 1 — else triangle 0.
  const int which = across.fraction + down.fraction > 1.0 ? 0 : 1;
  const std::array<Eigen::Vector3d, 3> held = lattice.cell_triangle(row, col, which);
  if (const auto hit = triangle_hit(held, ray)) return *hit;
  if (const auto hit = triangle_hit(lattice.cell_triangle(row, col, 1 - which), ray)) return *hit;
  std::optional<TriangleHit> nearest;
  for (int r = row - 1; r <= row + 1; ++r) {
    for (int c = col - 1; c <= col + 1; ++c) {
      if ((r == row && c == col) || r < 0 || c < 0 || r > lattice.nrows - 2 ||
          c > lattice.ncols - 2 || !lattice.cell_has_heights(r, c)) {
        continue;
      }
      for (int t = 0; t < 2; ++t) {
        const auto hit = triangle_hit(lattice.cell_triangle(r, c, t), ray);
        if (hit && (!nearest || hit->t < nearest->t)) nearest = hit;
      }
    }
  }
  if (nearest) return *nearest;
  return plane_hit(ray.origin_enu_m, ray.dir_enu, held[0], held[1], held[2]);
}

}  // namespace owsim
