#include "geometry/post_lattice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

// The two triangles of cell (row, col) as post (row, col) pairs: split along the diagonal from
// (row + 1, col) to (row, col + 1).
using Corner = std::array<int, 2>;
std::array<std::array<Corner, 3>, 2> cell_triangles(int row, int col) {
  const Corner a{row + 1, col}, b{row + 1, col + 1}, c{row, col + 1}, d{row, col};
  return {{{a, b, c}, {a, c, d}}};
}

// Twice the signed area of (p, q, r) seen from above (east, north).
double signed_area2(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
}

// The height at (e, n) on triangle (p, q, r) if (e, n) lies inside it (edges included, with a
// relative tolerance so a point on a shared edge belongs to both).
std::optional<double> height_in(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                const Eigen::Vector3d& r, double e, double n) {
  const double area = signed_area2(p, q, r);
  if (area == 0.0) return std::nullopt;
  const Eigen::Vector3d x(e, n, 0.0);
  const double wp = signed_area2(x, q, r) / area;
  const double wq = signed_area2(p, x, r) / area;
  const double wr = 1.0 - wp - wq;
  constexpr double kEdge = -1e-9;
  if (wp < kEdge || wq < kEdge || wr < kEdge) return std::nullopt;
  return wp * p.z() + wq * q.z() + wr * r.z();
}

}  // namespace

void PostLattice::validate(std::string_view where) const {
  const std::string at(where);
  if (ncols < 2 || nrows < 2) {
    throw Error(at + ": a DEM needs at least 2 × 2 posts, got " + std::to_string(ncols) + " × " +
                std::to_string(nrows));
  }
  const auto count = static_cast<std::size_t>(ncols) * static_cast<std::size_t>(nrows);
  if (posts.size() != count || valid.size() != count) {
    throw Error(at + ": the DEM's posts do not fill its " + std::to_string(ncols) + " × " +
                std::to_string(nrows) + " lattice");
  }
  for (const Eigen::Vector3d& post : posts) {
    if (!post.allFinite()) throw Error(at + ": a DEM post has a non-finite position");
  }
}

PostLattice::Location PostLattice::locate(double e_m, double n_m) const {
  // A first guess of the fractional (row, col) from the lattice's corners, then a walk: each step
  // re-solves in the cell reached, with that cell's own edge vectors, until (e, n) lies in it.
  const Eigen::Vector3d& origin = post(0, 0);
  Eigen::Matrix2d axes;
  axes.col(0) = (post(0, ncols - 1) - origin).head<2>() / (ncols - 1);  // per column
  axes.col(1) = (post(nrows - 1, 0) - origin).head<2>() / (nrows - 1);  // per row
  Eigen::Vector2d fraction = axes.inverse() * (Eigen::Vector2d(e_m, n_m) - origin.head<2>());
  const auto clamp_cell = [&](double x, int cells) {
    return std::clamp(static_cast<int>(std::floor(x)), 0, cells - 1);
  };
  int col = clamp_cell(fraction.x(), ncols - 1), row = clamp_cell(fraction.y(), nrows - 1);
  for (int step = 0; step < 16; ++step) {
    const Eigen::Vector3d& corner = post(row, col);
    Eigen::Matrix2d local;
    local.col(0) = (post(row, col + 1) - corner).head<2>();
    local.col(1) = (post(row + 1, col) - corner).head<2>();
    const Eigen::Vector2d inside = local.inverse() * (Eigen::Vector2d(e_m, n_m) - corner.head<2>());
    const int next_col = clamp_cell(col + inside.x(), ncols - 1);
    const int next_row = clamp_cell(row + inside.y(), nrows - 1);
    if (next_col == col && next_row == row) break;
    col = next_col;
    row = next_row;
  }
  // The cell reached and its neighbours: the triangle that holds (e, n). On an edge shared with
  // a hole, the cell with heights answers.
  Location location;
  for (int dr : {0, -1, 1}) {
    for (int dc : {0, -1, 1}) {
      const int r = row + dr, c = col + dc;
      if (r < 0 || c < 0 || r > nrows - 2 || c > ncols - 2) continue;
      for (const auto& triangle : cell_triangles(r, c)) {
        const auto height =
            height_in(post(triangle[0][0], triangle[0][1]), post(triangle[1][0], triangle[1][1]),
                      post(triangle[2][0], triangle[2][1]), e_m, n_m);
        if (!height) continue;
        location.inside = true;
        if (cell_has_heights(r, c)) {
          location.height_m = height;
          return location;
        }
      }
    }
  }
  return location;
}

double PostLattice::height_at(double e_m, double n_m) const {
  const Location location = locate(e_m, n_m);
  if (location.height_m) return *location.height_m;
  throw Error(
      "DEM: (" + std::to_string(e_m) + ", " + std::to_string(n_m) + ") m lies " +
      (location.inside ? "in a NODATA hole of the DEM" : "outside the part of the DEM loaded"));
}

bool PostLattice::covers(double e_m, double n_m) const { return locate(e_m, n_m).inside; }

bool PostLattice::cell_has_heights(int row, int col) const {
  return valid[index(row, col)] != 0 && valid[index(row + 1, col)] != 0 &&
         valid[index(row, col + 1)] != 0 && valid[index(row + 1, col + 1)] != 0;
}

std::array<Eigen::Vector3d, 3> PostLattice::cell_triangle(int row, int col, int which) const {
  const auto corners = cell_triangles(row, col)[static_cast<std::size_t>(which)];
  std::array<Eigen::Vector3d, 3> triangle{post(corners[0][0], corners[0][1]),
                                          post(corners[1][0], corners[1][1]),
                                          post(corners[2][0], corners[2][1])};
  // Counter-clockwise from above whichever way the raster's rows and columns run.
  if (signed_area2(triangle[0], triangle[1], triangle[2]) < 0.0)
    std::swap(triangle[1], triangle[2]);
  return triangle;
}

TriangleMesh PostLattice::mesh(const Eigen::AlignedBox2d& region) const {
  TriangleMesh mesh;
  if (region.isEmpty()) return mesh;
  if (posts.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("DEM: the mesh would exceed 2^32 vertices");
  }
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> vertex_of_post(posts.size(), kUnused);
  const auto vertex = [&](const Corner& corner) {
    const std::size_t i = index(corner[0], corner[1]);
    if (vertex_of_post[i] == kUnused) {
      vertex_of_post[i] = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.push_back(posts[i]);
    }
    return vertex_of_post[i];
  };
  for (int row = 0; row + 1 < nrows; ++row) {
    for (int col = 0; col + 1 < ncols; ++col) {
      if (!cell_has_heights(row, col)) continue;
      Eigen::AlignedBox2d box;
      for (const Corner& corner : {Corner{row, col}, Corner{row + 1, col}, Corner{row, col + 1},
                                   Corner{row + 1, col + 1}}) {
        box.extend(post(corner[0], corner[1]).head<2>());
      }
      if (!box.intersects(region)) continue;
      for (const auto& triangle : cell_triangles(row, col)) {
        std::array<std::uint32_t, 3> t{vertex(triangle[0]), vertex(triangle[1]),
                                       vertex(triangle[2])};
        // Counter-clockwise from above whichever way the raster's rows and columns run.
        if (signed_area2(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) < 0.0) {
          std::swap(t[1], t[2]);
        }
        mesh.triangles.push_back(t);
      }
    }
  }
  return mesh;
}

}  // namespace owsim
