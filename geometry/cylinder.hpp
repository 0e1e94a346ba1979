#pragma once
// Ray against a vertical solid cylinder — a pole or a tree (SENSOR-SPEC §6, source eq 6.7–6.10).
//
// The source's quadratic (eq 6.10) with the axis V = up reduces to the horizontal components:
// |o_h + t·d_h|² = r². It is solved about the closest approach t_c = −(o_h·d_h)/|d_h|², with the
// half chord √((r² − d²)/|d_h|²), so a ray from kilometres away keeps ~1e-12 m precision. The
// cylinder is closed (side wall, top cap, bottom cap) and convex; only surfaces the ray enters
// count, so a ray starting inside the solid hits nothing. A helicopter looking down sees the top
// cap of a tree. Valid for finite inputs, unit_dir of length 1, radius and height ≥ 0.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "geometry/scene.hpp"

namespace owsim {

enum class CylinderFace { wall, top, bottom };

// Made with all four fields; no member initialisers, so an array of them (the tracer's per-block
// cylinder hits) is not written when it is made.
struct CylinderHit {
  double t;                // range along the ray (unit_dir has length 1)
  Eigen::Vector3d normal;  // outward unit normal at the hit
  double axis_distance_m;  // d: distance between the ray line and the axis line
  CylinderFace face;
};

// Nearest entering hit with t ∈ [t_min, t_max], or nullopt  (SENSOR-SPEC §6, eq 6.7–6.10)
[[nodiscard]] std::optional<CylinderHit> intersect(const Cylinder& cylinder,
                                                   const Eigen::Vector3d& origin,
                                                   const Eigen::Vector3d& unit_dir, double t_min,
                                                   double t_max);

// The axis-aligned box around the cylinder.
[[nodiscard]] Eigen::AlignedBox3d bounds(const Cylinder& cylinder);

}  // namespace owsim
