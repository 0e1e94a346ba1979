#include "geometry/ray_segment.hpp"

#include <algorithm>
#include <cmath>

namespace owsim {
namespace {

// One feasible (t, s) pair and its squared distance.
struct Trial {
  double t = 0.0;
  double s = 0.0;
  double distance_sq = 0.0;
};

Trial evaluate(const Eigen::Vector3d& offset, const Eigen::Vector3d& dir,
               const Eigen::Vector3d& edge, double t, double s) {
  return {t, s, (offset + t * dir - s * edge).squaredNorm()};
}

// Keeps the nearer trial; among equally near ones (parallel lines), the one nearer the sensor.
void keep_best(Trial& best, const Trial& trial) {
  const double tolerance = 1e-12 * (1.0 + best.distance_sq);
  if (trial.distance_sq < best.distance_sq - tolerance ||
      (trial.distance_sq <= best.distance_sq + tolerance && trial.t < best.t)) {
    best = trial;
  }
}

}  // namespace

RaySegmentApproach closest_approach(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                    const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  // |w + t·u − s·e|² with w = origin − p0, u = dir, e = p1 − p0 (eq 7.3–7.4 as normal equations).
  const Eigen::Vector3d w = origin - p0;
  const Eigen::Vector3d e = p1 - p0;
  const double a = dir.squaredNorm();
  const double b = dir.dot(e);
  const double c = e.squaredNorm();
  const double d = dir.dot(w);
  const double f = e.dot(w);

  // The optimal t for a given s, and the optimal s for a given t, each clamped to its domain.
  const auto t_for = [&](double s) { return std::max(0.0, (b * s - d) / a); };
  const auto s_for = [&](double t) {
    return c > 0.0 ? std::clamp((f + b * t) / c, 0.0, 1.0) : 0.0;
  };

  // Boundary edges s = 0, s = 1 and t = 0: the minimum over the domain lies on one of them unless
  // the interior critical point is feasible (the squared distance is a convex quadratic).
  Trial best = evaluate(w, dir, e, t_for(0.0), 0.0);
  keep_best(best, evaluate(w, dir, e, t_for(1.0), 1.0));
  keep_best(best, evaluate(w, dir, e, 0.0, s_for(0.0)));

  // Interior critical point (eq 7.5–7.6), skipped for (nearly) parallel lines, where the edges
  // already hold a minimiser.
  const double determinant = a * c - b * b;
  if (determinant > 1e-14 * a * c) {
    const double s = (a * f - b * d) / determinant;
    const double t = (b * f - c * d) / determinant;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0) {
      // One refinement pass keeps the pair consistent when the system is ill-conditioned.
      const double t_refined = t_for(s);
      keep_best(best, evaluate(w, dir, e, t_refined, s_for(t_refined)));
    }
  }

  RaySegmentApproach approach;
  approach.ray_t = best.t;
  approach.segment_s = best.s;
  approach.distance_m = std::sqrt(best.distance_sq);
  approach.point_on_segment = p0 + best.s * e;
  return approach;
}

}  // namespace owsim
