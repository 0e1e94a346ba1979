#pragma once
// Where a ray runs inside an axis-aligned box: slab tests in double (Kay and Kajiya). Pure
// geometry, shared by the fog volumes and the wire pass's cull (engine/frame_tracer.cpp).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace owsim {

// Narrows [enter, exit] to where origin + t·dir has its coordinate between low and high; the
// stretch is left empty (exit < enter) when the ray never is. dir = 0 keeps it whole or empties it.
void clip_to_slab(double origin, double dir, double low, double high, double& enter, double& exit);

// Whether origin + t·dir, t ∈ [0, t_max], meets the box, its boundary included (an empty box:
// never).
[[nodiscard]] bool ray_meets_box(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin,
                                 const Eigen::Vector3d& dir, double t_max);

}  // namespace owsim
