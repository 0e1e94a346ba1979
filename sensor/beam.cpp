#include "sensor/beam.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

namespace owsim {
namespace {

// tan(divergence / 2), the last divergence's kept per thread: a scenario has one divergence, and
// the tangent of a constant was 1.4 % of a run's samples (libm's tan for every hit). Keyed by the
// divergence's bits, so every value (−0, NaN) gets its own tangent, bit for bit.
double half_divergence_tan(double divergence_mrad) {
  thread_local std::uint64_t last_bits = std::bit_cast<std::uint64_t>(0.0);
  thread_local double last_tan = 0.0;  // tan(0)
  const auto bits = std::bit_cast<std::uint64_t>(divergence_mrad);
  if (bits != last_bits) {
    last_tan = std::tan(0.5e-3 * divergence_mrad);
    last_bits = bits;
  }
  return last_tan;
}

}  // namespace

double beam_radius_m(double range_m, const BeamParams& beam) {
  return beam.exit_radius_m + range_m * half_divergence_tan(beam.divergence_mrad);
}

}  // namespace owsim
