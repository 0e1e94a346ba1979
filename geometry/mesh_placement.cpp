#include "geometry/mesh_placement.hpp"

#include <cmath>
#include <numbers>

namespace owsim {

Eigen::Vector3d placed_vertex(const Eigen::Vector3d& model, const MeshPlacement& placement) {
  const Eigen::Vector3d upright =
      placement.up == ModelUpAxis::z ? model : Eigen::Vector3d(model.x(), -model.z(), model.y());
  const double yaw = placement.yaw_deg * std::numbers::pi / 180.0;
  const double c = std::cos(yaw);
  const double s = std::sin(yaw);
  const Eigen::Vector3d scaled = placement.scale * upright;
  // Clockwise seen from above: north turns towards east.
  const Eigen::Vector3d turned(c * scaled.x() + s * scaled.y(), -s * scaled.x() + c * scaled.y(),
                               scaled.z());
  return placement.at_enu_m + turned;
}

TriangleMesh placed_mesh(const TriangleMesh& model, const MeshPlacement& placement) {
  TriangleMesh placed;
  placed.triangles = model.triangles;
  placed.vertices.reserve(model.vertices.size());
  for (const Eigen::Vector3d& vertex : model.vertices) {
    placed.vertices.push_back(placed_vertex(vertex, placement));
  }
  return placed;
}

}  // namespace owsim
