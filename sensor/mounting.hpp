#pragma once
// Where each pulse points: the chain of frames from the fiber array to the world (SENSOR-SPEC §4,
// source ch. 5 and ch. 9, "Pinned conventions").
//
//   ARC unit ray (a, b, c) = (sin α, cos α sin β, cos α cos β)           eq 9.1–9.3
//   SRC  v_src = (c, a, b)                                               X_src = C, Y_src = A,
//   Z_src = B model v = R_model · v_src, R_model = I (HELLAS) or Rx(−90°) (MilOWS) → MilOWS v = (c,
//   b, −a) body v_body = R_mount · v, R_mount = Rz(yaw)·Ry(pitch)·Rx(roll)      scenario mount NED
//   v_ned = Rz(heading)·Ry(pitch)·Rx(roll) · v_body                 eq 5.1–5.5 ENU  (e, n, u) =
//   (y_ned, x_ned, −z_ned), then the pose's local-level → frame rotation
//
// What follows for the sensors, at zero mount and attitude: MilOWS looks forward at α = β = 0,
// β positive to the right, α positive up (fiber 1, α = −21°, looks down; fiber 65 up). HELLAS
// (PRC = SRC) has α positive to the right and β positive down. Mount pitch −4° tilts the
// boresight 4° down. The sensor origin is the body origin + R · lever arm (body frame, metres).
// Exact to rounding (~1e-15 in each direction component); any finite angles.
#include <Eigen/Core>
#include <utility>

#include "geometry/rotation.hpp"
#include "sensor/sensor_model.hpp"

namespace owsim {

// The sensor's installation on the airframe (scenario `sensor.mount`).
struct Mount {
  double roll_deg = 0;
  double pitch_deg = 0;  // negative looks down
  double yaw_deg = 0;
  Eigen::Vector3d lever_arm_m = Eigen::Vector3d::Zero();  // body frame (X fwd, Y right, Z down)
};

// The aircraft's state at one instant, in the scenario's local ENU frame.
struct Pose {
  double time_s = 0;
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();  // body origin
  Attitude attitude;  // relative to the local-level North-East-Down axes at the position
  // Local-level ENU axes at the position → the frame's ENU axes: LocalFrame::enu_rotation_at.
  // Identity at the origin; leaving it identity elsewhere mis-points rays by ~0.009° per km.
  Eigen::Matrix3d frame_from_local_enu = Eigen::Matrix3d::Identity();
};

// ARC unit ray (a, b, c) = (sin α, cos α sin β, cos α cos β)  (SENSOR-SPEC §4, eq 9.1–9.3)
[[nodiscard]] Eigen::Vector3d arc_unit_ray(double alpha_deg, double beta_deg);
// The same from sin α and cos α (a fiber's, taken once by whoever places many of its pulses).
[[nodiscard]] Eigen::Vector3d arc_unit_ray(double sin_alpha, double cos_alpha, double beta_deg);
// sin α and cos α as arc_unit_ray takes them.
[[nodiscard]] std::pair<double, double> alpha_sin_cos(double alpha_deg);
// SRC from ARC, unrotated: (X, Y, Z)_src = (c, a, b)  (SENSOR-SPEC §4 pinned conventions)
[[nodiscard]] Eigen::Vector3d src_from_arc(const Eigen::Vector3d& abc);
// R_model: identity for HELLAS, Rx(−90°) for MilOWS  (SENSOR-SPEC §4 pinned conventions)
[[nodiscard]] Eigen::Matrix3d model_rotation(SensorModel model);
// R_mount = Rz(yaw)·Ry(pitch)·Rx(roll)  (SENSOR-SPEC §4 pinned conventions)
[[nodiscard]] Eigen::Matrix3d mount_rotation(const Mount& mount);
// v_body = R_mount · R_model · v_src(α, β), a unit vector  (SENSOR-SPEC §4 pinned conventions)
[[nodiscard]] Eigen::Vector3d ray_direction_body(SensorModel model, const Mount& mount,
                                                 double alpha_deg, double beta_deg);

// One pose's sensor placement, computed once per pose so a pulse costs one matrix–vector product.
struct SensorPlacement {
  Eigen::Matrix3d enu_from_src = Eigen::Matrix3d::Identity();
  Eigen::Vector3d origin_enu_m = Eigen::Vector3d::Zero();
};

// enu_from_src = F · enu_from_ned · R(attitude) · R_mount · R_model (F = frame_from_local_enu);
// origin = position + F · enu_from_ned · R(attitude) · lever_arm  (SENSOR-SPEC §4)
[[nodiscard]] SensorPlacement sensor_placement(const Pose& pose, const Mount& mount,
                                               SensorModel model);
// The same with body_from_src = R_mount · R_model made once by the caller.
[[nodiscard]] SensorPlacement sensor_placement(const Pose& pose,
                                               const Eigen::Matrix3d& body_from_src,
                                               const Eigen::Vector3d& lever_arm_m);
// The ray of fiber angle α and ray β in the frame's ENU axes, a unit vector  (SENSOR-SPEC §4)
[[nodiscard]] Eigen::Vector3d ray_direction_enu(const SensorPlacement& placement, double alpha_deg,
                                                double beta_deg);

}  // namespace owsim
