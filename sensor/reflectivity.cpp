#include "sensor/reflectivity.hpp"

#include <Eigen/Geometry>

namespace owsim {

double wire_incidence_deg(const Eigen::Vector3d& ray_dir, const Eigen::Vector3d& wire_axis) {
  // 90° − acute angle(ray, axis) = atan2(|cos|, |sin|), well conditioned at both ends.
  return acute_angle_deg(std::abs(ray_dir.dot(wire_axis)), ray_dir.cross(wire_axis).norm());
}

double surface_incidence_deg(const Eigen::Vector3d& ray_dir, const Eigen::Vector3d& normal) {
  return surface_incidence_deg(ray_dir.x(), ray_dir.y(), ray_dir.z(), normal.x(), normal.y(),
                               normal.z());
}

}  // namespace owsim
