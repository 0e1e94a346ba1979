#include "geometry/ray_triangle.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace owsim {
namespace {

// Barycentric slack at the edges. Rounding makes u and v uncertain by ~1e-13 for a ray from a
// kilometre away at grazing incidence, so a ray through a shared edge or corner could miss both
// triangles (Möller–Trumbore is not watertight); 1e-9 of an edge closes that gap and widens a
// triangle by a micrometre at most.
constexpr double kEdgeTolerance = 1e-9;

}  // namespace

std::optional<TriangleHit> intersect_triangle(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& dir, const Eigen::Vector3d& v0,
                                              const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                                              double t_min, double t_max) {
  const Eigen::Vector3d edge1 = v1 - v0;
  const Eigen::Vector3d edge2 = v2 - v0;
  const Eigen::Vector3d p = dir.cross(edge2);
  const double det = edge1.dot(p);
  if (det == 0.0 || !std::isfinite(det)) return std::nullopt;
  const double inv_det = 1.0 / det;
  const Eigen::Vector3d s = origin - v0;
  const double u = s.dot(p) * inv_det;
  if (u < -kEdgeTolerance || u > 1.0 + kEdgeTolerance) return std::nullopt;
  const Eigen::Vector3d q = s.cross(edge1);
  const double v = dir.dot(q) * inv_det;
  if (v < -kEdgeTolerance || u + v > 1.0 + kEdgeTolerance) return std::nullopt;
  const double t = edge2.dot(q) * inv_det;
  if (!(t >= t_min && t <= t_max)) return std::nullopt;
  return TriangleHit{t, edge1.cross(edge2).normalized()};
}

TriangleHit plane_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                      const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                      const Eigen::Vector3d& v2) {
  const Eigen::Vector3d normal = (v1 - v0).cross(v2 - v0).normalized();
  return {normal.dot(v0 - origin) / normal.dot(dir), normal};
}

TriangleHit exact_mesh_hit(const TriangleMesh& mesh, std::size_t index,
                           const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const auto& triangle = mesh.triangles[index];
  const Eigen::Vector3d& v0 = mesh.vertices[triangle[0]];
  const Eigen::Vector3d& v1 = mesh.vertices[triangle[1]];
  const Eigen::Vector3d& v2 = mesh.vertices[triangle[2]];
  if (const auto exact = intersect_triangle(origin, dir, v0, v1, v2, 0.0,
                                            std::numeric_limits<double>::infinity())) {
    return *exact;
  }
  return plane_hit(origin, dir, v0, v1, v2);
}

}  // namespace owsim
