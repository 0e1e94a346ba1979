#include "geometry/rotation.hpp"

#include <cmath>
#include <numbers>

namespace owsim {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace

Eigen::Matrix3d rotation_x_deg(double angle_deg) {
  const double c = std::cos(angle_deg * kRadPerDeg), s = std::sin(angle_deg * kRadPerDeg);
  Eigen::Matrix3d r;
  r << 1, 0, 0,  //
      0, c, -s,  //
      0, s, c;
  return r;
}

Eigen::Matrix3d rotation_y_deg(double angle_deg) {
  const double c = std::cos(angle_deg * kRadPerDeg), s = std::sin(angle_deg * kRadPerDeg);
  Eigen::Matrix3d r;
  r << c, 0, s,  //
      0, 1, 0,   //
      -s, 0, c;
  return r;
}

Eigen::Matrix3d rotation_z_deg(double angle_deg) {
  const double c = std::cos(angle_deg * kRadPerDeg), s = std::sin(angle_deg * kRadPerDeg);
  Eigen::Matrix3d r;
  r << c, -s, 0,  //
      s, c, 0,    //
      0, 0, 1;
  return r;
}

Eigen::Matrix3d body_to_ned(const Attitude& attitude) {
  return rotation_z_deg(attitude.heading_deg) * rotation_y_deg(attitude.pitch_deg) *
         rotation_x_deg(attitude.roll_deg);
}

Attitude attitude_from_body_to_ned(const Eigen::Matrix3d& r) {
  // R = Rz(ψ)Ry(θ)Rx(φ): R20 = −sin θ, R00 = cos ψ cos θ, R10 = sin ψ cos θ,
  // R21 = cos θ sin φ, R22 = cos θ cos φ; with φ = 0, R01 = −sin ψ and R11 = cos ψ.
  const double cos_pitch = std::hypot(r(0, 0), r(1, 0));
  Attitude attitude;
  attitude.pitch_deg = std::atan2(-r(2, 0), cos_pitch) * kDegPerRad;
  double heading_rad = 0.0;
  if (cos_pitch < 1e-9) {
    attitude.roll_deg = 0.0;
    heading_rad = std::atan2(-r(0, 1), r(1, 1));
  } else {
    attitude.roll_deg = std::atan2(r(2, 1), r(2, 2)) * kDegPerRad;
    heading_rad = std::atan2(r(1, 0), r(0, 0));
  }
  double heading_deg = heading_rad * kDegPerRad;
  if (heading_deg < 0.0) heading_deg += 360.0;
  if (heading_deg >= 360.0) heading_deg = 0.0;  // −tiny + 360 rounds to 360
  attitude.heading_deg = heading_deg;
  if (attitude.roll_deg == -180.0) attitude.roll_deg = 180.0;
  return attitude;
}

Eigen::Vector3d enu_from_ned(const Eigen::Vector3d& ned) { return {ned.y(), ned.x(), -ned.z()}; }

Eigen::Vector3d ned_from_enu(const Eigen::Vector3d& enu) { return {enu.y(), enu.x(), -enu.z()}; }

Eigen::Matrix3d enu_from_ned_matrix() {
  Eigen::Matrix3d m;
  m << 0, 1, 0,  //
      1, 0, 0,   //
      0, 0, -1;
  return m;
}

}  // namespace owsim
