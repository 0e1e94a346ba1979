#include "geometry/cylinder.hpp"

#include <cmath>

namespace owsim {

std::optional<CylinderHit> intersect(const Cylinder& cylinder, const Eigen::Vector3d& origin,
                                     const Eigen::Vector3d& unit_dir, double t_min, double t_max) {
  const Eigen::Vector3d o = origin - cylinder.base_enu_m;
  const Eigen::Vector2d o_h = o.head<2>(), d_h = unit_dir.head<2>();
  const double r = cylinder.radius_m, top = cylinder.height_m;
  const double a = d_h.squaredNorm();  // eq 6.10: a = D·D − (D·V)²

  // Closest approach of the ray line to the axis, in the horizontal plane.
  double t_closest = 0.0;
  Eigen::Vector2d closest = o_h;
  if (a > 0.0) {
    t_closest = -o_h.dot(d_h) / a;
    closest = o_h + t_closest * d_h;
  }
  const double axis_distance_sq = closest.squaredNorm();

  std::optional<CylinderHit> best;
  const auto consider = [&](double t, const Eigen::Vector3d& normal, CylinderFace face) {
    if (!(t >= t_min && t <= t_max)) return;
    if (best && !(t < best->t)) return;
    best = CylinderHit{t, normal, 0.0, face};
  };

  // Side wall: the entering root of eq 6.10, within the height.
  if (a > 0.0 && axis_distance_sq < r * r) {
    const double t = t_closest - std::sqrt((r * r - axis_distance_sq) / a);
    const double z = o.z() + t * unit_dir.z();
    if (z >= 0.0 && z <= top) {
      const Eigen::Vector2d radial = o_h + t * d_h;
      const Eigen::Vector2d outward = radial.normalized();  // |radial| = r > 0 here
      consider(t, Eigen::Vector3d(outward.x(), outward.y(), 0.0), CylinderFace::wall);
    }
  }
  // Caps: entered from above (top) or from below (bottom).
  const auto cap = [&](double z_cap, double z_sign, CylinderFace face) {
    if (!(unit_dir.z() * z_sign < 0.0)) return;
    const double t = (z_cap - o.z()) / unit_dir.z();
    if ((o_h + t * d_h).squaredNorm() <= r * r) consider(t, Eigen::Vector3d(0, 0, z_sign), face);
  };
  cap(top, 1.0, CylinderFace::top);
  cap(0.0, -1.0, CylinderFace::bottom);

  if (best) best->axis_distance_m = std::sqrt(axis_distance_sq);
  return best;
}

Eigen::AlignedBox3d bounds(const Cylinder& cylinder) {
  const Eigen::Vector3d reach(cylinder.radius_m, cylinder.radius_m, 0.0);
  return {cylinder.base_enu_m - reach,
          cylinder.base_enu_m + reach + Eigen::Vector3d(0, 0, cylinder.height_m)};
}

}  // namespace owsim
