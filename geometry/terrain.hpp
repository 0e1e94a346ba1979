#pragma once
// The ground under the scene (SENSOR-SPEC §6–7, DESIGN.md "Engine decisions": a triangle mesh
// from a height grid, a flat plane by default).
//
// Four kinds: none (no ground surface; objects are anchored at u = 0), flat (the plane
// u = flat_u_m), grid (a HeightGrid, bilinear between its samples; outside the grid's extent or
// next to a NODATA sample height_at throws owsim::Error, so an object placed off the map is a
// scenario error rather than a guess), dem (a PostLattice: a DEM's posts reprojected into ENU,
// its triangles the surface; height_at throws likewise). mesh() gives the engine its triangles,
// counter-clockwise seen from above (normals point up). The grid mesh splits each lattice cell
// along its SW–NE diagonal; inside a cell the planar triangles differ from the bilinear height_at
// by at most |z_sw + z_ne − z_se − z_nw| / 4.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/height_grid.hpp"
#include "geometry/post_lattice.hpp"
#include "geometry/triangle_mesh.hpp"

namespace owsim {

enum class TerrainKind { none, flat, grid, dem };

struct Terrain {
  TerrainKind kind = TerrainKind::flat;
  double flat_u_m = 0.0;  // kind == flat: the plane's height
  HeightGrid grid;        // kind == grid
  // kind == dem: a DEM's posts, reprojected (geometry/post_lattice.hpp); shared and immutable, so
  // a copy of the terrain (scenario → scene) does not copy millions of posts.
  std::shared_ptr<const PostLattice> dem;
  double reflectivity = 0.2;  // SENSOR-SPEC §7 ground default

  // Height of the ground at (e, n): none → 0, flat → flat_u_m, grid → bilinear, dem → on its
  // triangles (grid and dem may throw).
  [[nodiscard]] double height_at(double e_m, double n_m) const;
  // Triangles covering `region` (east = x, north = y): none → empty; flat → two triangles on the
  // region's corners; grid → two per lattice cell overlapping the region, clipped to the grid
  // (whole cells, not cut at the region's edge), cells with a NODATA corner skipped; dem → its
  // triangles overlapping the region. An empty region gives an empty mesh. Throws owsim::Error
  // beyond 2^32 vertices.
  [[nodiscard]] TriangleMesh mesh(const Eigen::AlignedBox2d& region) const;
};

}  // namespace owsim
