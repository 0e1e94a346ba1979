#pragma once
// The scene's objects as `owsim view` draws them on the map and in 3D, in local ENU metres:
//   {"wires": [{"id", "points": [[e,n,u], …]}],  each conductor's polyline thinned to at most
//                                                  kReportWireVertices vertices (ends kept)
//    "cylinders": [[e, n, u_base, height, radius, class code], …]   poles and trees (at most
//                                                  max_cylinders, evenly chosen; the count says)
//    "cylinders_total": N,
//    "meshes": [{"id", "class", "box": [e0, n0, u0, e1, n1, u1]}]}  a mesh by its bounding box
// The page draws conductors as lines; catenary sag at 64 vertices a span is off by at most a few
// centimetres, far below a pixel.
#include <cstddef>
#include <nlohmann/json.hpp>

#include "geometry/scene.hpp"

namespace owsim {

inline constexpr std::size_t kReportWireVertices = 64;

[[nodiscard]] nlohmann::json report_scene_json(const Scene& scene, std::size_t max_cylinders);

}  // namespace owsim
