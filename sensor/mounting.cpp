#include "sensor/mounting.hpp"

#include <cmath>
#include <numbers>

namespace owsim {

std::pair<double, double> alpha_sin_cos(double alpha_deg) {
  const double alpha = alpha_deg * (std::numbers::pi / 180.0);
  return {std::sin(alpha), std::cos(alpha)};
}

Eigen::Vector3d arc_unit_ray(double sin_alpha, double cos_alpha, double beta_deg) {
  const double beta = beta_deg * (std::numbers::pi / 180.0);
  return {sin_alpha, cos_alpha * std::sin(beta), cos_alpha * std::cos(beta)};
}

Eigen::Vector3d arc_unit_ray(double alpha_deg, double beta_deg) {
  const auto [sin_alpha, cos_alpha] = alpha_sin_cos(alpha_deg);
  return arc_unit_ray(sin_alpha, cos_alpha, beta_deg);
}

Eigen::Vector3d src_from_arc(const Eigen::Vector3d& abc) { return {abc.z(), abc.x(), abc.y()}; }

Eigen::Matrix3d model_rotation(SensorModel model) {
  if (model == SensorModel::hellas) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d rx_minus_90;  // Rx(−90°) written out, so that (c, a, b) ↦ (c, b, −a) exactly
  rx_minus_90 << 1, 0, 0,       //
      0, 0, 1,                  //
      0, -1, 0;
  return rx_minus_90;
}

Eigen::Matrix3d mount_rotation(const Mount& mount) {
  return rotation_z_deg(mount.yaw_deg) * rotation_y_deg(mount.pitch_deg) *
         rotation_x_deg(mount.roll_deg);
}

Eigen::Vector3d ray_direction_body(SensorModel model, const Mount& mount, double alpha_deg,
                                   double beta_deg) {
  return mount_rotation(mount) * model_rotation(model) *
         src_from_arc(arc_unit_ray(alpha_deg, beta_deg));
}

SensorPlacement sensor_placement(const Pose& pose, const Mount& mount, SensorModel model) {
  return sensor_placement(pose, mount_rotation(mount) * model_rotation(model), mount.lever_arm_m);
}

SensorPlacement sensor_placement(const Pose& pose, const Eigen::Matrix3d& body_from_src,
                                 const Eigen::Vector3d& lever_arm_m) {
  const Eigen::Matrix3d enu_from_body =
      pose.frame_from_local_enu * enu_from_ned_matrix() * body_to_ned(pose.attitude);
  SensorPlacement placement;
  placement.enu_from_src = enu_from_body * body_from_src;
  placement.origin_enu_m = pose.position_enu_m + enu_from_body * lever_arm_m;
  return placement;
}

Eigen::Vector3d ray_direction_enu(const SensorPlacement& placement, double alpha_deg,
                                  double beta_deg) {
  return placement.enu_from_src * src_from_arc(arc_unit_ray(alpha_deg, beta_deg));
}

}  // namespace owsim
