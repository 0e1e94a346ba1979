#pragma once
// Ray against one triangle in double precision (Möller & Trumbore, "Fast, minimum storage
// ray/triangle intersection", 1997). Used to turn the engine's float terrain hit into an exact
// range, and by the brute-force reference tracer. Both faces count (a ray from below a terrain
// triangle hits it too). Edges and corners count with a barycentric slack of 1e-9, so a ray
// through an edge or corner shared by two triangles hits at least one of them despite rounding.
// Valid for finite inputs; degenerate triangles never hit.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/ray_box.hpp"
#include "geometry/triangle_mesh.hpp"

namespace owsim {

// Barycentric slack at the edges. Rounding makes u and v uncertain by ~1e-13 for a ray from a
// kilometre away at grazing incidence, so a ray through a shared edge or corner could miss both
// triangles (Möller–Trumbore is not watertight); 1e-9 of an edge closes that gap and widens a
// triangle by a micrometre at most.
inline constexpr double kTriangleEdgeTolerance = 1e-9;

struct TriangleHit {
  double t = 0.0;                                    // range along the ray (unit dir)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit normal, (v1−v0)×(v2−v0) direction
};

// What the test needs of a triangle that does not depend on the ray: its first corner, edges and
// unit normal — computed once for a mesh traced many times, with the same bits.
struct TriangleFrame {
  Eigen::Vector3d v0, edge1, edge2;  // edge1 = v1 − v0, edge2 = v2 − v0
  Eigen::Vector3d normal;            // (v1−v0)×(v2−v0), normalised
};

[[nodiscard]] TriangleFrame triangle_frame(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                           const Eigen::Vector3d& v2);
// Every triangle's frame, by index.
[[nodiscard]] std::vector<TriangleFrame> triangle_frames(const TriangleMesh& mesh);

// Nearest hit with t ∈ [t_min, t_max], or nullopt.
[[nodiscard]] std::optional<TriangleHit> intersect_triangle(
    const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& v0,
    const Eigen::Vector3d& v1, const Eigen::Vector3d& v2, double t_min, double t_max);
[[nodiscard]] std::optional<TriangleHit> intersect_triangle(const Eigen::Vector3d& origin,
                                                            const Eigen::Vector3d& dir,
                                                            const TriangleFrame& triangle,
                                                            double t_min, double t_max);

// For rays [0, n) of a block at once (the tracer's level ground, engine/embree_scene.hpp): the
// first of `triangles` that intersect_triangle accepts for ray i with t ∈ [0, rays.t_max[i]] —
// ranges[i] its t, the same bits (the same operations in the same order, over arrays), and
// which[i] its index — else ranges[i] NaN (which[i] then unspecified). n ≤ RayArrays::kCapacity
// (geometry/ray_triangle_batch.cpp).
void first_triangle_hits(std::span<const TriangleFrame> triangles, const RayArrays& rays,
                         std::size_t n, double* ranges, std::int64_t* which);

// The ray's range and normal on the plane of triangle (v0, v1, v2), the normal in the
// (v1−v0)×(v2−v0) direction: where a float tracer put the ray on this triangle while the double
// ray passes just over its edge (its t would be off by the float rounding of origin and
// direction, millimetres at grazing incidence). Valid for a ray not parallel to the plane.
[[nodiscard]] TriangleHit plane_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                    const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                    const Eigen::Vector3d& v2);

// The ray on triangle `index` of `mesh` in double: intersect_triangle over all t ≥ 0, else
// plane_hit.
[[nodiscard]] TriangleHit exact_mesh_hit(const TriangleMesh& mesh, std::size_t index,
                                         const Eigen::Vector3d& origin, const Eigen::Vector3d& dir);
// The same from the mesh's frames (triangle_frames): the same bits, without the per-hit edges,
// cross product and square root.
[[nodiscard]] TriangleHit exact_mesh_hit(const std::vector<TriangleFrame>& frames,
                                         std::size_t index, const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& dir);

}  // namespace owsim
