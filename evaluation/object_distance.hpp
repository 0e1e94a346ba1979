#pragma once
// How far a point is from a scene object's surface (owsim score's gate, docs/evidence.md
// "Scoring a detector"): a conductor as its polyline thickened by its radius, a pole or tree as a
// solid vertical cylinder, a mesh by its triangles (nearest point on each, Ericson's
// region test). Zero inside or on the object; exact to rounding.
#include <Eigen/Core>
#include <cstdint>

#include "geometry/scene.hpp"

namespace owsim {

// The distance from `point_enu_m` to named object `object` (< named_object_count(scene)).
[[nodiscard]] double distance_to_object_m(const Scene& scene, std::uint32_t object,
                                          const Eigen::Vector3d& point_enu_m);

// The point of triangle (a, b, c) nearest to p.
[[nodiscard]] Eigen::Vector3d nearest_on_triangle(const Eigen::Vector3d& p,
                                                  const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b,
                                                  const Eigen::Vector3d& c);

}  // namespace owsim
