// first_triangle_hits (geometry/ray_triangle.hpp): Möller–Trumbore over arrays of rays, vectorised.
// Compiled with -fno-trapping-math (CMakeLists.txt): GCC vectorises the loop only when it may
// evaluate every operation of a lane, whatever its tests gave (a lane with det = 0 divides by it;
// the flags are never read, and the lane is masked).
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/error.hpp"
#include "geometry/ray_triangle.hpp"
#include "geometry/vector_clones.hpp"

namespace owsim {
namespace {

// Rays still without a hit (range NaN) that meet the triangle get its t and `index`.
// intersect_triangle's arithmetic, operation for operation: Eigen's cross product is
// (a1·b2 − a2·b1, a2·b0 − a0·b2, a0·b1 − a1·b0) and its dot product of 3-vectors
// (a0·b0 + a1·b1) + a2·b2; "avx2" enables no FMA, so nothing is fused. The index is an int64 so
// that every array of the loop has the lanes of a double: a byte array made GCC take 32 rays an
// iteration and spill most of them to the stack.
OWSIM_VECTOR_CLONES void first_hits_of(const double (&v0)[3], const double (&e1)[3],
                                       const double (&e2)[3], std::int64_t index,
                                       const RayArrays& rays, std::size_t n,
                                       double* __restrict ranges, std::int64_t* __restrict which) {
  constexpr double kMaxFinite = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < n; ++i) {
    const double d0 = rays.dir[0][i], d1 = rays.dir[1][i], d2 = rays.dir[2][i];
    const double p0 = d1 * e2[2] - d2 * e2[1];
    const double p1 = d2 * e2[0] - d0 * e2[2];
    const double p2 = d0 * e2[1] - d1 * e2[0];
    const double det = (e1[0] * p0 + e1[1] * p1) + e1[2] * p2;
    const double inv_det = 1.0 / det;
    const double s0 = rays.origin[0][i] - v0[0];
    const double s1 = rays.origin[1][i] - v0[1];
    const double s2 = rays.origin[2][i] - v0[2];
    const double u = ((s0 * p0 + s1 * p1) + s2 * p2) * inv_det;
    const double q0 = s1 * e1[2] - s2 * e1[1];
    const double q1 = s2 * e1[0] - s0 * e1[2];
    const double q2 = s0 * e1[1] - s1 * e1[0];
    const double v = ((d0 * q0 + d1 * q1) + d2 * q2) * inv_det;
    const double t = ((e2[0] * q0 + e2[1] * q1) + e2[2] * q2) * inv_det;
    // det ≠ 0 and finite; u, v inside with the slack; t ∈ [0, t_max] (a NaN fails every test).
    // Every test evaluated (& rather than &&), so the lanes need no branch.
    const bool hit = (det != 0.0) & (std::abs(det) <= kMaxFinite) & (u >= -kTriangleEdgeTolerance) &
                     (u <= 1.0 + kTriangleEdgeTolerance) & (v >= -kTriangleEdgeTolerance) &
                     (u + v <= 1.0 + kTriangleEdgeTolerance) & (t >= 0.0) & (t <= rays.t_max[i]);
    const bool take = hit & (ranges[i] != ranges[i]);  // not yet hit: NaN
    ranges[i] = take ? t : ranges[i];
    which[i] = take ? index : which[i];
  }
}

}  // namespace

void first_triangle_hits(std::span<const TriangleFrame> triangles, const RayArrays& rays,
                         std::size_t n, double* ranges, std::int64_t* which) {
  if (n > RayArrays::kCapacity) throw Error("ray triangle: more rays than a block holds");
  std::fill(ranges, ranges + n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const TriangleFrame& triangle = triangles[k];
    const double v0[3] = {triangle.v0.x(), triangle.v0.y(), triangle.v0.z()};
    const double e1[3] = {triangle.edge1.x(), triangle.edge1.y(), triangle.edge1.z()};
    const double e2[3] = {triangle.edge2.x(), triangle.edge2.y(), triangle.edge2.z()};
    first_hits_of(v0, e1, e2, static_cast<std::int64_t>(k), rays, n, ranges, which);
  }
}

}  // namespace owsim
