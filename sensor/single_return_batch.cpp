#include "sensor/single_return_batch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/vector_clones.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/receiver_noise.hpp"

namespace owsim {
namespace {

struct Constants {
  bool noisy;
  double threshold;
  double noise_at_1km;
  double range_noise_sigma_m;
  double counts_per_m;
  double timeout_counts;
};

// The decision of each slot. Every condition is a 0.0 / 1.0 double (and = product, or = max) and
// every choice a select, so the loop has one lane width and no branch and GCC vectorises it; each
// quantity is computed by the expression of the scalar path it stands for. The outcome is a
// SingleReturnBatch::Outcome as a double.
OWSIM_VECTOR_CLONES void decide(const Constants& c, std::size_t n, const double* __restrict range_m,
                                const double* __restrict energy_rel,
                                const double* __restrict background,
                                const double* __restrict normal, double* __restrict noisy_range_m,
                                double* __restrict counts_out, double* __restrict outcome) {
  constexpr double kLargest = std::numeric_limits<double>::max();
  const double noisy = c.noisy ? 1.0 : 0.0;
  const double threshold = c.threshold;
  const double noise_at_1km = c.noise_at_1km;
  const double sigma_range = c.range_noise_sigma_m;
  const double range_noise = sigma_range != 0.0 ? 1.0 : 0.0;
  const double counts_per_m = c.counts_per_m;
  const double timeout = c.timeout_counts;
  for (std::size_t i = 0; i < n; ++i) {
    const double range = range_m[i];
    const double energy = energy_rel[i];
    const double range_finite = std::abs(range) <= kLargest ? 1.0 : 0.0;  // 0 for NaN
    const double finite = std::abs(energy) <= kLargest ? range_finite : 0.0;
    // Registers: §7's test (registers), or §11's echo far from the threshold
    // (ReceiverNoise::echo_registers; within kSureEchoSigmas σ_n a keyed draw decides).
    const double margin = energy - threshold;
    const double r = range / 1000.0;
    const double sigma = noise_at_1km * r * r * std::sqrt(1.0 + background[i]);  // noise_sigma
    const double bound = kSureEchoSigmas * sigma;
    const double sure_in = sigma > 0.0 ? (margin > bound ? 1.0 : 0.0) : (margin >= 0.0 ? 1.0 : 0.0);
    const double sure_out =
        sigma > 0.0 ? (margin < -bound ? 1.0 : 0.0) : (margin < 0.0 ? 1.0 : 0.0);
    const double plain = energy >= threshold ? range_finite : 0.0;
    const double registers = noisy * finite * sure_in + (1.0 - noisy) * plain;
    const double undecided_echo = noisy * finite * (1.0 - sure_in) * (1.0 - sure_out);
    // The range noise (record_returns: the range itself when σ = 0) and the counter
    // (RangeCounter::counter, whose division near a rounding boundary is left to it).
    const double z = normal[i];
    const double with_noise = range + sigma_range * z;
    const double noisy_range = sigma_range != 0.0 ? with_noise : range;
    const double normal_unknown = z == z ? 0.0 : range_noise;
    const double counts = noisy_range * counts_per_m;
    const double magnitude = std::abs(counts);
    const double truncated = std::trunc(magnitude);  // the int64 round trip, below 2^52
    const double fraction = magnitude - truncated;
    const double boundary = std::abs(fraction - 0.5) < 1e-9 ? 1.0 : 0.0;
    const double near_boundary = magnitude < 0x1p52 ? boundary : 0.0;
    // counter_from_counts: round_half_away (for 2^52 and beyond, NaN and ∞ the count itself),
    // then into 0..timeout; at the timeout there is no return.
    const double up = fraction >= 0.5 ? 1.0 : 0.0;
    const double rounded = std::copysign(truncated + up, counts);
    const double in_gate = rounded < timeout ? 1.0 : 0.0;  // 0 for NaN
    counts_out[i] = rounded <= 0.0 ? 0.0 : rounded;
    noisy_range_m[i] = noisy_range < 0.0 ? 0.0 : noisy_range;  // std::max(range, 0.0): −0 kept
    const double undecided =
        std::max(undecided_echo, registers * std::max(normal_unknown, near_boundary));
    outcome[i] = undecided != 0.0 ? 2.0 : registers * in_gate;
  }
}

}  // namespace

SingleReturnBatch::SingleReturnBatch(const ReceiverParams& p, bool noisy)
    : noisy_(noisy),
      threshold_(p.threshold),
      noise_at_1km_(p.noise.noise_at_1km),
      range_noise_sigma_m_(owsim::range_noise_sigma_m(p)),
      counts_per_m_(1.0 / range_per_count_m(p.counter)),
      timeout_counts_(p.counter.timeout_counts) {}

void SingleReturnBatch::evaluate() {
  decide(Constants{noisy_, threshold_, noise_at_1km_, range_noise_sigma_m_, counts_per_m_,
                   static_cast<double>(timeout_counts_)},
         size_, range_m_, energy_rel_, background_, normal_, noisy_range_m_, counts_, outcome_);
}

}  // namespace owsim
