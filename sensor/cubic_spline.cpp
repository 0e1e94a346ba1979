#include "sensor/cubic_spline.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/error.hpp"

namespace owsim {

CubicSpline::CubicSpline(std::vector<double> x, std::vector<double> y)
    : x_(std::move(x)), y_(std::move(y)) {
  const std::size_t n = x_.size();
  if (n != y_.size()) throw Error("cubic spline: the abscissae and ordinates differ in length");
  if (n < 2) throw Error("cubic spline: needs at least two knots, got " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x_[i]) || !std::isfinite(y_[i])) {
      throw input_error("cubic spline knot " + std::to_string(i), "value is not finite");
    }
    if (i > 0 && !(x_[i] > x_[i - 1])) {
      throw input_error("cubic spline knot " + std::to_string(i),
                        "abscissa does not increase strictly");
    }
  }
  // h_i−1 z_i−1 + 2 (h_i−1 + h_i) z_i + h_i z_i+1 = 6 (Δ_i − Δ_i−1), Δ_i = (y_i+1 − y_i)/h_i,
  // z_0 = z_n−1 = 0: forward elimination then back substitution (Thomas algorithm).
  z_.assign(n, 0.0);
  if (n < 3) return;
  std::vector<double> upper(n, 0.0), rhs(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h_left = x_[i] - x_[i - 1];
    const double h_right = x_[i + 1] - x_[i];
    const double slope_left = (y_[i] - y_[i - 1]) / h_left;
    const double slope_right = (y_[i + 1] - y_[i]) / h_right;
    const double pivot = 2.0 * (h_left + h_right) - h_left * upper[i - 1];
    upper[i] = h_right / pivot;
    rhs[i] = (6.0 * (slope_right - slope_left) - h_left * rhs[i - 1]) / pivot;
  }
  for (std::size_t i = n - 2; i >= 1; --i) z_[i] = rhs[i] - upper[i] * z_[i + 1];
}

std::size_t CubicSpline::interval(double x) const {
  const auto upper = std::upper_bound(x_.begin() + 1, x_.end() - 1, x);
  return static_cast<std::size_t>(upper - x_.begin()) - 1;
}

double CubicSpline::value_in(std::size_t i, double x) const {
  if (x < x_.front()) return y_.front();
  if (x > x_.back()) return y_.back();
  const double h = x_[i + 1] - x_[i];
  const double a = x - x_[i];      // distance from the left knot
  const double b = x_[i + 1] - x;  // distance to the right knot
  return (z_[i + 1] * a * a * a + z_[i] * b * b * b) / (6.0 * h) +
         (y_[i + 1] / h - h * z_[i + 1] / 6.0) * a + (y_[i] / h - h * z_[i] / 6.0) * b;
}

CubicSpline::Sample CubicSpline::evaluate_in(std::size_t i, double x) const {
  if (x < x_.front()) return {y_.front(), 0.0};
  if (x > x_.back()) return {y_.back(), 0.0};
  const double h = x_[i + 1] - x_[i];
  const double a = x - x_[i];      // distance from the left knot
  const double b = x_[i + 1] - x;  // distance to the right knot
  const double value = value_in(i, x);
  const double derivative = (z_[i + 1] * a * a - z_[i] * b * b) / (2.0 * h) +
                            (y_[i + 1] - y_[i]) / h - h * (z_[i + 1] - z_[i]) / 6.0;
  return {value, derivative};
}

double CubicSpline::second_derivative(double x) const {
  if (x < x_.front() || x > x_.back()) return 0.0;
  const std::size_t i = interval(x);
  const double t = (x - x_[i]) / (x_[i + 1] - x_[i]);
  return (1.0 - t) * z_[i] + t * z_[i + 1];
}

}  // namespace owsim
