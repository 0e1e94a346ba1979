#include "sensor/footprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace owsim {
namespace {

// Taylor coefficients of φ − sin φ = φ³·Σ c_k·φ^(2k): (−1)^k / (2k + 3)!, k = 0..6.
constexpr std::array<double, 7> kAngleMinusSineSeries = {
    1.0 / 6.0,        -1.0 / 120.0,        1.0 / 5040.0,         -1.0 / 362880.0,
    1.0 / 39916800.0, -1.0 / 6227020800.0, 1.0 / 1307674368000.0};

// φ − sin φ, by its Taylor series below 0.5 rad (relative error < 1e-18) where the difference
// would cancel.
double angle_minus_sine(double phi) {
  if (phi > 0.5) return phi - std::sin(phi);
  const double p2 = phi * phi;
  double sum = 0.0;
  for (auto k = kAngleMinusSineSeries.size(); k-- > 0;) sum = sum * p2 + kAngleMinusSineSeries[k];
  return phi * p2 * sum;
}

}  // namespace

double circle_segment_area_m2(double x_m, double radius_m) {
  if (!(radius_m > 0.0) || x_m >= radius_m) return 0.0;
  const double disc = std::numbers::pi * radius_m * radius_m;
  if (x_m <= -radius_m) return disc;
  if (x_m < 0.0) return disc - circle_segment_area_m2(-x_m, radius_m);
  // With θ = acos(x/R): S = R²·θ − x·√(R² − x²) = ½R²·(2θ − sin 2θ), stable as x → R.
  const double half_angle = std::atan2(std::sqrt((radius_m - x_m) * (radius_m + x_m)), x_m);
  return 0.5 * radius_m * radius_m * angle_minus_sine(2.0 * half_angle);
}

double circle_strip_overlap_m2(double d_m, double half_width_m, double radius_m) {
  const double area = circle_segment_area_m2(d_m - half_width_m, radius_m) -
                      circle_segment_area_m2(d_m + half_width_m, radius_m);
  return std::max(0.0, area);
}

double footprint_fraction(double d_m, double half_width_m, double beam_radius_m) {
  if (!(beam_radius_m > 0.0)) {
    const double offset = std::abs(d_m);
    return offset < half_width_m ? 1.0 : offset == half_width_m ? 0.5 : 0.0;
  }
  const double disc = std::numbers::pi * beam_radius_m * beam_radius_m;
  return std::clamp(circle_strip_overlap_m2(d_m, half_width_m, beam_radius_m) / disc, 0.0, 1.0);
}

double segment_area_from_height_m2(double height_m, double radius_m) {
  const double apothem = radius_m - height_m;  // centre-to-chord distance
  return radius_m * radius_m * std::acos(apothem / radius_m) -
         apothem * std::sqrt(2.0 * radius_m * height_m - height_m * height_m);
}

double chord_strip_area_m2(double d_m, double half_width_m, double radius_m) {
  const double chord = 2.0 * std::sqrt(radius_m * radius_m - d_m * d_m);
  return chord * 2.0 * half_width_m;
}

}  // namespace owsim
