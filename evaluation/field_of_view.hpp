#pragma once
// The part of a straight segment that lies inside a frame's scanned field (INTERFACE.md "Ground
// truth and detection evidence", docs/evidence.md "In view"): the set of directions the sensor's
// rays span in one frame, α from the lowest to the highest fiber and β from the sweep's first to
// its last ray (sawtooth included), out to the counter's timeout range. α and β are the angles of
// SENSOR-SPEC §4 (eq 9.1–9.3): a point at sensor-frame offset v = (X, Y, Z)_src has ARC components
// (a, b, c) = (Y, Z, X), α = asin(a / |v|) and β = atan2(b, c).
//
// Method: each bound is a half-space, a ball or a circular cone about the ARC a axis, so along
// p + t·d each is exact in t: β ≥ β₁ and β ≤ β₂ are linear (planes through the a axis), |v| ≤ R
// and the α bounds quadratic (a ≥ |v| sin α is the inside of a convex cone for α ≥ 0 and the
// outside of one for α < 0). The segment's in-field part is the intersection of these intervals
// (at most three pieces); the nearest point to the sensor is the clamped minimiser of |v(t)|² on
// each. Exact to rounding for any finite input with β₂ − β₁ < 180° and both within ±90°; no
// sampling, so a segment that only grazes a corner of the field is found.
#include <Eigen/Core>
#include <optional>

namespace owsim {

// The field one frame scans, in the sensor's SRC axes (degrees, metres).
struct ScanField {
  double alpha_min_deg = 0.0;
  double alpha_max_deg = 0.0;
  double beta_min_deg = 0.0;
  double beta_max_deg = 0.0;
  double range_max_m = 0.0;
};

// α and β of a sensor-frame offset (SRC axes)  (SENSOR-SPEC §4, eq 9.1–9.3 inverted)
struct FieldAngles {
  double alpha_deg = 0.0;
  double beta_deg = 0.0;
};
[[nodiscard]] FieldAngles field_angles(const Eigen::Vector3d& v_src);

// A field with its bounds' sines and cosines made once: a segment costs a few dozen flops.
// Const and allocation-free: thread-safe.
class FieldOfView {
 public:
  explicit FieldOfView(const ScanField& field);

  [[nodiscard]] const ScanField& field() const { return field_; }
  // True when the sensor-frame offset lies in the field (boundary included): its α, β and range
  // within the bounds, tested without inverse trigonometry (the half-spaces and cones of
  // nearest_inside).
  [[nodiscard]] bool contains(const Eigen::Vector3d& v_src) const;
  // False when a sphere (centre as a sensor-frame offset) lies wholly outside the field; true may
  // still find nothing inside. The β bounds as planes, α and range by the sphere's angular radius.
  [[nodiscard]] bool may_hold_sphere(const Eigen::Vector3d& centre_src, double radius_m) const;
  // True when segment p0–p1 lies wholly outside a convex part of the field's complement (beyond a
  // β plane, below a negative lowest α or above a positive highest α) — a few multiplications; false
  // may still hold nothing inside.
  [[nodiscard]] bool wholly_outside(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) const;
  // The nearest point to the sensor of segment p0–p1 (sensor-frame offsets, SRC axes) inside the
  // field, as its parameter t ∈ [0, 1] along p0 → p1; std::nullopt when no part of it is inside.
  [[nodiscard]] std::optional<double> nearest_inside(const Eigen::Vector3d& p0,
                                                     const Eigen::Vector3d& p1) const;

 private:
  ScanField field_;
  double sin_alpha_min_ = 0.0, sin_alpha_max_ = 0.0;
  double sin_beta_min_ = 0.0, cos_beta_min_ = 0.0, sin_beta_max_ = 0.0, cos_beta_max_ = 0.0;
};

// The parameter t ∈ [0, 1] of the point of segment p0–p1 nearest the origin.
[[nodiscard]] double nearest_on_segment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1);

}  // namespace owsim
