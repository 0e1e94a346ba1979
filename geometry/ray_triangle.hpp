#pragma once
// Ray against one triangle in double precision (Möller & Trumbore, "Fast, minimum storage
// ray/triangle intersection", 1997). Used to turn the engine's float terrain hit into an exact
// range, and by the brute-force reference tracer. Both faces count (a ray from below a terrain
// triangle hits it too). Edges and corners count with a barycentric slack of 1e-9, so a ray
// through an edge or corner shared by two triangles hits at least one of them despite rounding.
// Valid for finite inputs; degenerate triangles never hit.
#include <Eigen/Core>
#include <optional>

namespace owsim {

struct TriangleHit {
  double t = 0.0;                                    // range along the ray (unit dir)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit normal, (v1−v0)×(v2−v0) direction
};

// Nearest hit with t ∈ [t_min, t_max], or nullopt.
[[nodiscard]] std::optional<TriangleHit> intersect_triangle(
    const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& v0,
    const Eigen::Vector3d& v1, const Eigen::Vector3d& v2, double t_min, double t_max);

}  // namespace owsim
