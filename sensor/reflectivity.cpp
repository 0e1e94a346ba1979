#include "sensor/reflectivity.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace owsim {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// The quartic of eq 7.12, valid on 0°..45°.
constexpr double reflectivity_fit_pct(double theta_deg) {
  return (((9.3e-6 * theta_deg - 0.00064) * theta_deg - 0.0058) * theta_deg) * theta_deg +
         kReflectivityNormalPct;
}

}  // namespace

double reflectivity_pct(double incidence_deg) {
  const double theta = std::abs(incidence_deg);
  if (theta <= 45.0) return reflectivity_fit_pct(theta);
  if (theta < 90.0) return reflectivity_fit_pct(45.0) * (90.0 - theta) / 45.0;
  return 0.0;
}

double wire_incidence_deg(const Eigen::Vector3d& ray_dir, const Eigen::Vector3d& wire_axis) {
  // 90° − acute angle(ray, axis) = atan2(|cos|, |sin|), well conditioned at both ends.
  return kDegPerRad * std::atan2(std::abs(ray_dir.dot(wire_axis)), ray_dir.cross(wire_axis).norm());
}

double surface_incidence_deg(const Eigen::Vector3d& ray_dir, const Eigen::Vector3d& normal) {
  return kDegPerRad * std::atan2(ray_dir.cross(normal).norm(), std::abs(ray_dir.dot(normal)));
}

}  // namespace owsim
