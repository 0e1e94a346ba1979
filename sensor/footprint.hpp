#pragma once
// The beam footprint on a wire or cylinder silhouette (SENSOR-SPEC §7 Decision, source
// eq 7.8–7.10).
//
// The beam at the object is a uniform disc of radius R; the object's silhouette is a strip of
// half-width w (wire or cylinder radius) whose centre line passes at distance d from the disc
// centre. The covered area is exactly A(d) = S(d − w) − S(d + w), with S(x) the area of the disc
// beyond a chord at signed distance x from its centre:
//   S(x) = R²·acos(x/R) − x·√(R² − x²) for |x| ≤ R,  0 for x ≥ R,  πR² for x ≤ −R.
// The source's two cases are approximations kept for tests and documentation: case 1, a strip
// covering past one edge of the disc, is the circular segment of eq 7.8 (exact in that regime);
// case 2, a narrow strip inside the disc, is chord × width (eq 7.9–7.10; relative error ≈ w²/6R²
// for a central strip). Valid for any finite d, w ≥ 0, R ≥ 0; exact to rounding (≈ 1e-16·R²
// absolute in A).
namespace owsim {

// S(x): disc area beyond the chord at signed distance x from the centre  (SENSOR-SPEC §7)
[[nodiscard]] double circle_segment_area_m2(double x_m, double radius_m);
// A(d) = S(d − w) − S(d + w): disc area covered by a strip of half-width w at distance d
// (SENSOR-SPEC §7 Decision)
[[nodiscard]] double circle_strip_overlap_m2(double d_m, double half_width_m, double radius_m);
// a_fp / a_ls = A(d) / (πR²) in [0, 1]; for a point beam (R = 0): 1 inside the strip, ½ on its
// edge, 0 outside  (SENSOR-SPEC §7, eq 7.13)
[[nodiscard]] double footprint_fraction(double d_m, double half_width_m, double beam_radius_m);

// Source case 1: circular segment of height h (the depth of disc the strip covers), h ∈ [0, 2R]:
// R²·acos((R − h)/R) − (R − h)·√(2Rh − h²)  (SENSOR-SPEC §7, eq 7.8)
[[nodiscard]] double segment_area_from_height_m2(double height_m, double radius_m);
// Source case 2: a narrow strip wholly inside the disc as chord × width:
// c = 2·√(R² − d²), area = c · 2w  (SENSOR-SPEC §7, eq 7.9–7.10)
[[nodiscard]] double chord_strip_area_m2(double d_m, double half_width_m, double radius_m);

}  // namespace owsim
