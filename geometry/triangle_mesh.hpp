#pragma once
// A triangle mesh in the local ENU frame: the terrain the engine hands Embree, or a placed model.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace owsim {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;                // local ENU metres
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices (terrain: CCW from above)
};

}  // namespace owsim
