#include "geometry/ray_triangle.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace owsim {

TriangleFrame triangle_frame(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                             const Eigen::Vector3d& v2) {
  const Eigen::Vector3d edge1 = v1 - v0;
  const Eigen::Vector3d edge2 = v2 - v0;
  return {v0, edge1, edge2, edge1.cross(edge2).normalized()};
}

std::vector<TriangleFrame> triangle_frames(const TriangleMesh& mesh) {
  std::vector<TriangleFrame> frames;
  frames.reserve(mesh.triangles.size());
  for (const auto& triangle : mesh.triangles) {
    frames.push_back(triangle_frame(mesh.vertices[triangle[0]], mesh.vertices[triangle[1]],
                                    mesh.vertices[triangle[2]]));
  }
  return frames;
}

std::optional<TriangleHit> intersect_triangle(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& dir,
                                              const TriangleFrame& triangle, double t_min,
                                              double t_max) {
  const Eigen::Vector3d& edge1 = triangle.edge1;
  const Eigen::Vector3d& edge2 = triangle.edge2;
  const Eigen::Vector3d p = dir.cross(edge2);
  const double det = edge1.dot(p);
  if (det == 0.0 || !std::isfinite(det)) return std::nullopt;
  const double inv_det = 1.0 / det;
  const Eigen::Vector3d s = origin - triangle.v0;
  const double u = s.dot(p) * inv_det;
  if (u < -kTriangleEdgeTolerance || u > 1.0 + kTriangleEdgeTolerance) return std::nullopt;
  const Eigen::Vector3d q = s.cross(edge1);
  const double v = dir.dot(q) * inv_det;
  if (v < -kTriangleEdgeTolerance || u + v > 1.0 + kTriangleEdgeTolerance) return std::nullopt;
  const double t = edge2.dot(q) * inv_det;
  if (!(t >= t_min && t <= t_max)) return std::nullopt;
  return TriangleHit{t, triangle.normal};
}

std::optional<TriangleHit> intersect_triangle(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& dir, const Eigen::Vector3d& v0,
                                              const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                                              double t_min, double t_max) {
  return intersect_triangle(origin, dir, triangle_frame(v0, v1, v2), t_min, t_max);
}

namespace {

TriangleHit plane_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                      const TriangleFrame& triangle) {
  return {triangle.normal.dot(triangle.v0 - origin) / triangle.normal.dot(dir), triangle.normal};
}

}  // namespace

TriangleHit plane_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                      const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                      const Eigen::Vector3d& v2) {
  return plane_hit(origin, dir, triangle_frame(v0, v1, v2));
}

TriangleHit exact_mesh_hit(const std::vector<TriangleFrame>& frames, std::size_t index,
                           const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const TriangleFrame& triangle = frames[index];
  if (const auto exact =
          intersect_triangle(origin, dir, triangle, 0.0, std::numeric_limits<double>::infinity())) {
    return *exact;
  }
  return plane_hit(origin, dir, triangle);
}

TriangleHit exact_mesh_hit(const TriangleMesh& mesh, std::size_t index,
                           const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const auto& triangle = mesh.triangles[index];
  const TriangleFrame frame = triangle_frame(mesh.vertices[triangle[0]], mesh.vertices[triangle[1]],
                                             mesh.vertices[triangle[2]]);
  if (const auto exact =
          intersect_triangle(origin, dir, frame, 0.0, std::numeric_limits<double>::infinity())) {
    return *exact;
  }
  return plane_hit(origin, dir, frame);
}

}  // namespace owsim
