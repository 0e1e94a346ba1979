#pragma once
// A model's triangle mesh placed in the local ENU frame (scenario key meshes): scaled, its up axis
// turned to u, turned by its yaw, and moved to its position.
#include <Eigen/Core>

#include "geometry/triangle_mesh.hpp"

namespace owsim {

// Which of the model's axes points up. z: the model's (x, y, z) are (east, north, up) at yaw 0;
// y (the OBJ habit of Blender and most modelling tools, −z forward): (x, −z, y) are.
enum class ModelUpAxis { z, y };

struct MeshPlacement {
  Eigen::Vector3d at_enu_m = Eigen::Vector3d::Zero();  // where the model's origin goes
  double yaw_deg = 0.0;  // turned clockwise seen from above, like a heading: at 90 the model's
                         // north (+y for up z) points east
  double scale = 1.0;    // model units → metres
  ModelUpAxis up = ModelUpAxis::z;
};

// The model's vertex `model` in local ENU metres.
[[nodiscard]] Eigen::Vector3d placed_vertex(const Eigen::Vector3d& model,
                                            const MeshPlacement& placement);
// Every vertex placed, the triangles kept; a placement that mirrors nothing keeps the winding.
[[nodiscard]] TriangleMesh placed_mesh(const TriangleMesh& model, const MeshPlacement& placement);

}  // namespace owsim
