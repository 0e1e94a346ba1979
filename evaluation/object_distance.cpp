#include "evaluation/object_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace owsim {

Eigen::Vector3d nearest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Which Voronoi region of the triangle p projects into: a vertex, an edge or the face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return a;  // a degenerate triangle
  return a + ab * (vb / sum) + ac * (vc / sum);
}

double distance_to_object_m(const Scene& scene, std::uint32_t object,
                            const Eigen::Vector3d& point_enu_m) {
  std::size_t index = object;
  if (index < scene.conductors.size()) {
    const Conductor& conductor = scene.conductors[index];
    const std::vector<Eigen::Vector3d>& points = conductor.points_enu_m;
    double nearest2 = points.empty() ? 0.0 : (point_enu_m - points.front()).squaredNorm();
    for (std::size_t i = 1; i < points.size(); ++i) {
      const Eigen::Vector3d d = points[i] - points[i - 1];
      const double length2 = d.squaredNorm();
      const double t = length2 > 0.0
                           ? std::clamp((point_enu_m - points[i - 1]).dot(d) / length2, 0.0, 1.0)
                           : 0.0;
      nearest2 = std::min(nearest2, (point_enu_m - (points[i - 1] + t * d)).squaredNorm());
    }
    return std::max(0.0, std::sqrt(nearest2) - conductor.radius_m);
  }
  index -= scene.conductors.size();
  if (index < scene.cylinders.size()) {
    const Cylinder& cylinder = scene.cylinders[index];
    const double across = std::max(
        0.0, (point_enu_m.head<2>() - cylinder.base_enu_m.head<2>()).norm() - cylinder.radius_m);
    const double bottom = cylinder.base_enu_m.z();
    const double top = bottom + cylinder.height_m;
    const double up = point_enu_m.z() < bottom ? bottom - point_enu_m.z()
                      : point_enu_m.z() > top  ? point_enu_m.z() - top
                                               : 0.0;
    return std::hypot(across, up);
  }
  const TriangleMesh& mesh = scene.meshes[index - scene.cylinders.size()].mesh;
  double nearest2 = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d q = nearest_on_triangle(point_enu_m, mesh.vertices[t[0]],
                                                  mesh.vertices[t[1]], mesh.vertices[t[2]]);
    nearest2 = std::min(nearest2, (point_enu_m - q).squaredNorm());
  }
  return std::isfinite(nearest2) ? std::sqrt(nearest2) : std::numeric_limits<double>::infinity();
}

}  // namespace owsim
