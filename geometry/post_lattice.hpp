#pragma once
// Terrain given as a lattice of posts placed exactly in the local ENU frame: the samples of a DEM
// raster, each post the ENU position of a raster cell centre at its height, reprojected from the
// file's CRS (io/scenario/dem_terrain.hpp). The lattice need not be regular in ENU: a geographic
// raster's columns converge, a projected one is rotated by the grid convergence. Row r, column c
// is the raster's; neighbouring posts form cells.
//
// Surface: each cell whose four posts all hold a height is two planar triangles, split along the
// diagonal from post (r + 1, c) to post (r, c + 1); a cell with a NODATA post is a hole. Inside a
// cell the triangles differ from the bilinear interpolation of the four heights by at most
// |h00 + h11 − h01 − h10| / 4 (the cell's twist), to which the curvature of the reprojection adds
// well under a millimetre for cells of up to ~100 m. height_at() answers on these triangles, so
// objects stand exactly on the surface the pulses hit.
// Valid: ncols, nrows ≥ 2, posts.size() = valid.size() = ncols·nrows, finite coordinates.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace owsim {

struct PostLattice {
  int ncols = 0;
  int nrows = 0;
  std::vector<Eigen::Vector3d> posts;  // row-major, raster row 0 first; NODATA posts at height 0
  std::vector<std::uint8_t> valid;     // 1 where the post holds a height, 0 for NODATA

  [[nodiscard]] std::size_t index(int row, int col) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(ncols) +
           static_cast<std::size_t>(col);
  }
  [[nodiscard]] const Eigen::Vector3d& post(int row, int col) const {
    return posts[index(row, col)];
  }

  // Throws owsim::Error "<where>: …" if the lattice breaks the valid range above.
  void validate(std::string_view where) const;
  // Height of the surface at (e, n). Throws owsim::Error if (e, n) lies outside the lattice or in
  // a hole.
  [[nodiscard]] double height_at(double e_m, double n_m) const;
  // The height of the surface at (e, n), or nullopt outside the lattice or in a hole.
  [[nodiscard]] std::optional<double> height_if_any(double e_m, double n_m) const {
    return locate(e_m, n_m).height_m;
  }
  // Whether (e, n) lies within the lattice's cells (in a hole or not).
  [[nodiscard]] bool covers(double e_m, double n_m) const;
  // Whether all four posts of cell (row, col) hold heights (else the cell is a hole).
  [[nodiscard]] bool cell_has_heights(int row, int col) const;
  // Triangle `which` of cell (row, col), counter-clockwise from above: 0 is the one at post
  // (row + 1, col + 1), 1 the one at post (row, col).
  [[nodiscard]] std::array<Eigen::Vector3d, 3> cell_triangle(int row, int col, int which) const;
  // The triangles of every cell whose posts' box overlaps `region`, counter-clockwise from above.
  // Throws owsim::Error beyond 2^32 vertices.
  [[nodiscard]] TriangleMesh mesh(const Eigen::AlignedBox2d& region) const;

 private:
  struct Location {
    bool inside = false;             // within the lattice's cells
    std::optional<double> height_m;  // the surface's height there, unless in a hole
  };
  [[nodiscard]] Location locate(double e_m, double n_m) const;
};

}  // namespace owsim
