#pragma once
// Closest approach between a laser ray and a straight wire segment (SENSOR-SPEC §7, source
// eq 7.1–7.7, after Bourke [Bou98]).
//
// The ray is origin + t·dir with t ≥ 0 (the pulse leaves the sensor forwards only); the segment is
// p0 + s·(p1 − p0) with s ∈ [0, 1]. The source solves the two unbounded lines (eq 7.5–7.6); this
// returns the true minimum of the distance over the clamped domain t ≥ 0, s ∈ [0, 1]: the interior
// critical point when it lies inside, otherwise the best of the three boundary edges (t = 0, s = 0,
// s = 1), each an exactly clamped one-dimensional minimum. Parallel lines and a zero-length
// segment are handled (the nearest-t point among equally close ones is returned).
// Valid for any finite inputs with dir ≠ 0; double precision, exact to rounding (≈ 1e-12 m at
// km ranges).
#include <Eigen/Core>

namespace owsim {

struct RaySegmentApproach {
  double ray_t = 0.0;       // ray parameter at the closest point (the range along a unit dir)
  double segment_s = 0.0;   // 0..1 along p0 → p1
  double distance_m = 0.0;  // |ray point − segment point|
  Eigen::Vector3d point_on_segment = Eigen::Vector3d::Zero();
};

// Closest approach of ray (origin, dir, t ≥ 0) and segment p0–p1  (SENSOR-SPEC §7, eq 7.1–7.7)
[[nodiscard]] RaySegmentApproach closest_approach(const Eigen::Vector3d& origin,
                                                  const Eigen::Vector3d& dir,
                                                  const Eigen::Vector3d& p0,
                                                  const Eigen::Vector3d& p1);

}  // namespace owsim
