#pragma once
// A hanging wire between two supports (SENSOR-SPEC §6, source eq 6.11–6.14, drawing 14).
//
// In the vertical plane of the span, x runs from support 1 (x = 0) to support 2 (x = D) and y is
// the height above a common datum:  y(x) = S + a·(cosh((x − x0)/a) − 1),  vertex (x0, S).
// The source's equation (6.12) holds only for equal supports; this solves the general case:
// with h1 = H1 − S and h2 = H2 − S the vertex offsets are x0 = a·acosh(1 + h1/a) and
// D − x0 = a·acosh(1 + h2/a), so the parameter a is the root of
//     f(a) = a·acosh(1 + h1/a) + a·acosh(1 + h2/a) − D,
// which rises monotonically from −D (a → 0) to +∞ (a → ∞). The root is bracketed and found by
// Newton's method safeguarded by geometric bisection, to |f(a)| ≤ 1e-12·D or a relative step
// ≤ 1e-15 — both supports then lie on the curve to ~1e-9 m, far inside the spec's 1 mm.
// Valid range: D > 0, S ≤ min(H1, H2) with S < max(H1, H2) (S equal to the lower support puts
// the vertex at that support), all finite; 1e-12 < a/max(h1, h2) and a < 1e12·D (beyond these
// the wire hangs vertically or lies flat: rejected as unreachable). Heights and slopes are
// evaluated without cancellation (cosh − 1 as 2·sinh²), so they hold to rounding at any a.
#include <vector>

namespace owsim {

// The four numbers of drawing 14, all heights above one common datum.
struct CatenaryProfile {
  double span_m = 0.0;       // D: horizontal distance between the supports
  double support_1_m = 0.0;  // H1: attachment height at x = 0
  double support_2_m = 0.0;  // H2: attachment height at x = D
  double lowest_m = 0.0;     // S: height of the lowest point of the wire
};

class Catenary {
 public:
  // Solve for a and x0  (SENSOR-SPEC §6, eq 6.12–6.14). Throws owsim::Error for a non-finite
  // value, D ≤ 0, S above a support, S equal to both supports, or an unreachable D.
  [[nodiscard]] static Catenary solve(const CatenaryProfile& profile);

  [[nodiscard]] const CatenaryProfile& profile() const { return profile_; }
  [[nodiscard]] double parameter_m() const { return a_; }  // a, the curve parameter (eq 6.11)
  [[nodiscard]] double vertex_x_m() const { return x0_; }  // x0 ∈ [0, D]
  // y(x) = S + a·(cosh((x − x0)/a) − 1)  (SENSOR-SPEC §6, eq 6.11 shifted to the vertex)
  [[nodiscard]] double height_at(double x_m) const;
  // dy/dx = sinh((x − x0)/a)
  [[nodiscard]] double slope_at(double x_m) const;
  // Arc length from x = 0 to x = D: a·(sinh((D − x0)/a) + sinh(x0/a))
  [[nodiscard]] double length_m() const;
  // x positions 0 = x_0 < … < x_n = D whose polyline stays within max_chord_error_m of the curve
  // (perpendicular distance). The chord error of a step Δx is Δx²/(8a) to leading order at every
  // x (curvature 1/(a·cosh²) times the arc length Δx·cosh squared), so the steps are uniform with
  // Δx = 0.9·√(8·a·max_chord_error_m): the worst deviation is ≈ 0.81 of the bound. A 400 m span
  // with a ≈ 2000 m needs 113 points at 1 mm. Throws owsim::Error for a bound that is not > 0.
  [[nodiscard]] std::vector<double> sample_x(double max_chord_error_m = 0.001) const;

 private:
  Catenary(const CatenaryProfile& profile, double a, double x0)
      : profile_(profile), a_(a), x0_(x0) {}

  CatenaryProfile profile_;
  double a_ = 0.0;
  double x0_ = 0.0;
};

}  // namespace owsim
