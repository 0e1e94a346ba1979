#pragma once
// Rotations about the coordinate axes and the aircraft attitude (SENSOR-SPEC §4, source
// eq 5.1–5.5).
//
// All rotations are right-handed and active: R·v turns the vector v, it does not re-express it.
// The attitude matrix takes body vectors (X forward, Y right, Z down) to the local North-East-Down
// frame: R = Rz(heading) · Ry(pitch) · Rx(roll), heading clockwise from north, pitch nose-up
// positive, roll right-wing-down positive. East-North-Up is (e, n, u) = (y_NED, x_NED, −z_NED).
// Valid for any finite angle; double precision, orthonormal to ~1e-16.
#include <Eigen/Core>

namespace owsim {

// Rotation by angle_deg about X: Rx(φ) = [1 0 0; 0 cos −sin; 0 sin cos]  (SENSOR-SPEC §4, eq 5.4)
[[nodiscard]] Eigen::Matrix3d rotation_x_deg(double angle_deg);
// Rotation by angle_deg about Y: Ry(θ) = [cos 0 sin; 0 1 0; −sin 0 cos]  (SENSOR-SPEC §4, eq 5.3)
[[nodiscard]] Eigen::Matrix3d rotation_y_deg(double angle_deg);
// Rotation by angle_deg about Z: Rz(ψ) = [cos −sin 0; sin cos 0; 0 0 1]  (SENSOR-SPEC §4, eq 5.2)
[[nodiscard]] Eigen::Matrix3d rotation_z_deg(double angle_deg);

// Aircraft attitude, degrees: heading clockwise from (true) north, pitch nose-up positive,
// roll right-wing-down positive.
struct Attitude {
  double roll_deg = 0;
  double pitch_deg = 0;
  double heading_deg = 0;
};

// Body (X fwd, Y right, Z down) → NED: Rz(heading)·Ry(pitch)·Rx(roll)  (SENSOR-SPEC §4,
// eq 5.1, 5.5)
[[nodiscard]] Eigen::Matrix3d body_to_ned(const Attitude& attitude);

// The attitude of a body→NED rotation, the inverse of body_to_ned  (source eq 5.6–5.9)
// heading in [0°, 360°), pitch in [−90°, 90°], roll in (−180°, 180°]. At ±90° pitch (gimbal lock,
// |cos pitch| < 1e-9) heading and roll are not separable: roll is set to 0 and the whole
// rotation about the vertical is reported as heading.
[[nodiscard]] Attitude attitude_from_body_to_ned(const Eigen::Matrix3d& body_to_ned_matrix);

// (e, n, u) = (y_NED, x_NED, −z_NED), and back  (SENSOR-SPEC §4 pinned conventions)
[[nodiscard]] Eigen::Vector3d enu_from_ned(const Eigen::Vector3d& ned);
[[nodiscard]] Eigen::Vector3d ned_from_enu(const Eigen::Vector3d& enu);
// The matrix of enu_from_ned (a reflection-free axis swap, det = +1; its own inverse).
[[nodiscard]] Eigen::Matrix3d enu_from_ned_matrix();

}  // namespace owsim
