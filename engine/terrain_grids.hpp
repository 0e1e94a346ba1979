#pragma once
// A DEM's terrain as Embree grid primitives (RTC_GEOMETRY_TYPE_GRID) over the lattice's own posts
// (geometry/post_lattice.hpp), instead of a triangle mesh: Embree keeps one float3 per post and
// builds its compact grid BVH (~15 bytes a post in all), where a triangle mesh costs ~250 (double
// vertices kept for exact hits, float vertices and indices in Embree, a BVH over two triangles a
// post).
// Embree splits each grid quad along the diagonal from vertex (x + 1, y) to (x, y + 1) — the
// lattice's own diagonal from post (row, col + 1) to (row + 1, col) — so the float surface is the
// lattice's triangles.
//
// The lattice's cells are cut into tiles of kTileCells × kTileCells cells (a remainder of one cell
// joins the tile before it); a tile whose posts' box meets the region is one grid when all its
// cells hold heights, else its cells with heights are triangles (patches()), so holes stay holes.
// Grids thinner than 2 × 2 cells are never made: Embree 3.13 reports hits on a one-cell-high grid
// where the surface is not and misses it where it is (seen with a grid per row of cells).
// A grid hit (grid, u, v) names the cell; exact_grid_hit re-intersects that cell's triangles in
// double, as a triangle hit is (geometry/ray_triangle.hpp exact_mesh_hit).
#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "geometry/post_lattice.hpp"
#include "geometry/ray_triangle.hpp"
#include "geometry/triangle_mesh.hpp"
#include "sensor/pulse_candidates.hpp"

namespace owsim {

class TerrainGrids {
 public:
  static constexpr int kTileCells = 64;

  // The grids of `lattice`'s cells with heights in the tiles meeting `region`. The lattice must
  // outlive this object. Throws owsim::Error beyond 2^32 posts.
  TerrainGrids(const PostLattice& lattice, const Eigen::AlignedBox2d& region);

  [[nodiscard]] std::size_t grid_count() const { return grids_.size(); }
  // A new committed grid geometry holding the grids (the caller attaches and releases it);
  // only when grid_count() > 0.
  [[nodiscard]] RTCGeometry grid_geometry(RTCDevice device) const;
  // The triangles of the tiles with holes, counter-clockwise from above.
  [[nodiscard]] const TriangleMesh& patches() const { return patches_; }
  // The pulse's range and normal on the cell Embree reported (grid `prim_id`, its u, v), in
  // double: the cell's triangle holding (u, v), else its other triangle, else the nearest of the
  // neighbouring cells' (float rounding may put the float ray in a cell the double ray just
  // misses), else the plane of the triangle holding (u, v).
  [[nodiscard]] TriangleHit exact_grid_hit(unsigned prim_id, float u, float v,
                                           const PulseRay& ray) const;

 private:
  const PostLattice* lattice_;
  std::vector<RTCGrid> grids_;
  TriangleMesh patches_;
};

}  // namespace owsim
