#include "sensor/hellas_scan.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/error.hpp"

namespace owsim {

double hellas_mirror_angle_factor_deg(const ScanParams& p) {
  if (p.hellas_mirror_angle_factor_deg != 0.0) return p.hellas_mirror_angle_factor_deg;
  return p.sweep_deg / p.pulses_per_frame();
}

int hellas_ni_pulse(const ScanParams& p, const FrameSweep& sweep) {
  const int last = p.pulses_per_frame() - 1;
  const double half_maf = 0.5 * hellas_mirror_angle_factor_deg(p);
  const double first_beta = mirror_beta_deg(p, sweep, 0);
  const double last_beta = mirror_beta_deg(p, sweep, last);
  if (0.0 < std::min(first_beta, last_beta) - half_maf ||
      0.0 > std::max(first_beta, last_beta) + half_maf) {
    return -1;
  }
  // β is linear in the pulse index: solve β(k) = 0, then settle the rounding among neighbours.
  const double exact =
      -sweep.mirror_beta_start_deg * p.pulses_per_frame() / (sweep.direction * p.sweep_deg);
  const int guess = static_cast<int>(std::clamp(std::round(exact), 0.0, static_cast<double>(last)));
  int best = -1;
  double best_abs = 0.0;
  for (int k = std::max(0, guess - 1); k <= std::min(last, guess + 1); ++k) {
    const double beta_abs = std::abs(mirror_beta_deg(p, sweep, k));
    if (best < 0 || beta_abs < best_abs) {
      best = k;
      best_abs = beta_abs;
    }
  }
  return best;
}

double hellas_mirror_beta_deg(const ScanParams& p, int pulse, int ni_pulse, int direction) {
  return direction * (pulse - ni_pulse) * hellas_mirror_angle_factor_deg(p);
}

bool hellas_ain(const ScanParams& p, std::int64_t frame, int pulse) {
  const std::int64_t line = frame * p.lines_per_frame + pulse / p.fibers_per_line;
  return (line & 1) != 0;
}

std::uint16_t hellas_header_beta_code(double beta_start_deg) {
  if (!std::isfinite(beta_start_deg)) throw Error("HELLAS header: mirror angle is not finite");
  const double code =
      std::round((beta_start_deg + kHellasHeaderBetaOffsetDeg) / kHellasHeaderBetaStepDeg);
  return static_cast<std::uint16_t>(
      std::clamp(code, 0.0, static_cast<double>(kHellasHeaderCodeMax)));
}

double hellas_beta_from_header_code(std::uint16_t code) {
  return code * kHellasHeaderBetaStepDeg - kHellasHeaderBetaOffsetDeg;
}

}  // namespace owsim
