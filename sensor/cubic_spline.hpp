#pragma once
// Natural cubic spline interpolation of navigation channels (SENSOR-SPEC §5, source eq 10.2–10.3,
// after Numerical Recipes).
//
// On the interval [x_i, x_i+1], h_i = x_i+1 − x_i (eq 10.3) and with z the second derivatives:
//   S_i(x) = z_i+1 (x − x_i)³ / (6 h_i) + z_i (x_i+1 − x)³ / (6 h_i)
//          + (y_i+1 / h_i − h_i z_i+1 / 6)(x − x_i) + (y_i / h_i − h_i z_i / 6)(x_i+1 − x)
//          (eq 10.2)
// Natural end conditions z_0 = z_n−1 = 0; z from one tridiagonal solve (Thomas algorithm, O(n)).
// Two knots give the straight line. Evaluation is const and allocation-free (binary search for
// the interval), so one spline may be shared by many threads.
// Outside [x_0, x_n−1] the spline is held at its end value (derivative 0): callers ask inside.
// Accuracy: interpolates the knots to rounding; matches scipy CubicSpline(bc_type='natural').
#include <cstddef>
#include <vector>

namespace owsim {

class CubicSpline {
 public:
  struct Sample {
    double value = 0;
    double derivative = 0;  // d value / d x
  };

  CubicSpline() = default;
  // Fits the spline. Throws owsim::Error unless x and y have the same length ≥ 2, every value is
  // finite and x strictly increases (the message names the 0-based knot).
  CubicSpline(std::vector<double> x, std::vector<double> y);

  // S(x) and S'(x)  (SENSOR-SPEC §5, eq 10.2)
  [[nodiscard]] Sample evaluate(double x) const { return evaluate_in(interval(x), x); }
  [[nodiscard]] double value(double x) const { return value_in(interval(x), x); }
  [[nodiscard]] double derivative(double x) const { return evaluate(x).derivative; }
  // S''(x): linear between the knots' second derivatives; 0 outside the range.
  [[nodiscard]] double second_derivative(double x) const;

  // The interval i with x_i ≤ x < x_i+1 (clamped to the first and last), by binary search; splines
  // on the same knots can share one search.
  [[nodiscard]] std::size_t interval(double x) const;
  // S and S' on a known interval (x outside the knot range: the end value, derivative 0).
  [[nodiscard]] Sample evaluate_in(std::size_t interval, double x) const;
  // S alone on a known interval: evaluate_in's value, bit for bit, without the derivative's
  // divisions (a pose takes six of them twice a scan line)  (SENSOR-SPEC §5, eq 10.2)
  [[nodiscard]] double value_in(std::size_t interval, double x) const;

  [[nodiscard]] const std::vector<double>& knots_x() const { return x_; }
  [[nodiscard]] const std::vector<double>& knots_y() const { return y_; }
  [[nodiscard]] const std::vector<double>& second_derivatives() const { return z_; }

 private:
  std::vector<double> x_, y_, z_;
};

}  // namespace owsim
