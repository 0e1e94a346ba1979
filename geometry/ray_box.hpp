#pragma once
// Rays and axis-aligned boxes in double: where a ray runs inside one (slabs, Kay and Kajiya; the
// fog volumes), and whether a block of rays meets one (separating axes; the wire pass's cull,
// engine/frame_tracer.cpp). Pure geometry.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>

namespace owsim {

// Narrows [enter, exit] to where origin + t·dir has its coordinate between low and high; the
// stretch is left empty (exit < enter) when the ray never is. dir = 0 keeps it whole or empties it.
void clip_to_slab(double origin, double dir, double low, double high, double& enter, double& exit);

// A block of rays as arrays: ray i is origin[·][i] + t·dir[·][i], t ∈ [0, t_max[i]].
struct RayArrays {
  static constexpr std::size_t kCapacity = 256;
  alignas(64) double origin[3][kCapacity];
  alignas(64) double dir[3][kCapacity];
  alignas(64) double t_max[kCapacity];
};

// meets[i] = 1 when ray i of rays [0, n) meets the box, its boundary included (to rounding),
// else 0 (an empty box: never): separating axes, without a division or a branch. Finite rays,
// n ≤ kCapacity.
void rays_meet_box(const Eigen::AlignedBox3d& box, const RayArrays& rays, std::size_t n,
                   std::int64_t* meets);

}  // namespace owsim
