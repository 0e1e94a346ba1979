#include "sensor/motor_encoder.hpp"

#include <cmath>

namespace owsim {

double motor_angle_slope(double mirror_beta_deg) {
  double slope = 0.0;
  const int degree = static_cast<int>(kMotorPolynomial.size()) - 1;
  for (int i = 0; i < degree; ++i) {
    slope = slope * mirror_beta_deg + (degree - i) * kMotorPolynomial[static_cast<std::size_t>(i)];
  }
  return slope;
}

double mirror_beta_deg_from_motor_angle(double target_deg) {
  // φ decreases with β: φ(lo) is the largest angle, φ(hi) the smallest.
  double lo = -kMirrorBetaLimitDeg, hi = kMirrorBetaLimitDeg;
  if (!(target_deg < motor_angle_deg(lo))) return lo;
  if (!(target_deg > motor_angle_deg(hi))) return hi;
  double beta = (target_deg - motor_angle_deg(0.0)) / motor_angle_slope(0.0);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double residual = motor_angle_deg(beta) - target_deg;
    if (residual > 0.0)
      lo = beta;
    else
      hi = beta;
    double next = beta - residual / motor_angle_slope(beta);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    if (std::abs(next - beta) < 1e-12) return next;
    beta = next;
  }
  return beta;
}

double motor_angle_from_encoder_deg(EncoderCount count) { return count * kEncoderDegPerCount; }

EncoderCount encoder_from_mirror_beta(double mirror_beta_deg) {
  return encoder_count(motor_angle_deg(mirror_beta_deg));
}

double mirror_beta_deg_from_encoder(EncoderCount count) {
  return mirror_beta_deg_from_motor_angle(motor_angle_from_encoder_deg(count));
}

}  // namespace owsim
