#pragma once
// The range counter (SENSOR-SPEC §1): a 250 MHz timer, 12 bits wide, one tick = 0.59940 m of
// range, 2066 ticks = timeout (no return). Valid for ranges 0..timeout; the counter saturates.
#include <cmath>
#include <cstdint>

#include "geometry/exact_round.hpp"

namespace owsim {

struct RangeCounterParams {
  double speed_of_light_mps = 299'792'500.0;  // §1, as the source uses it
  double refractive_index_air = 1.0003;       // §1 n_air
  double timer_period_s = 4e-9;               // §1 T_res, 250 MHz clock
  std::uint16_t timeout_counts = 2066;        // §1 eq 9.4
};

inline constexpr std::uint16_t kCounterMax = 4095;  // 12-bit field

// Range per counter tick Δ = c·T_res / (2·n_air) = 0.59940 m  (SENSOR-SPEC §1, eq 3.2 decision / eq 9.4)
[[nodiscard]] double range_per_count_m(const RangeCounterParams& p);
// Range noise σ = Δ/√2 = 0.4241 m  (SENSOR-SPEC §1, eq 3.3)
[[nodiscard]] double default_range_noise_sigma_m(const RangeCounterParams& p);
// Range at the timeout count, 2066·Δ = 1238.36 m  (SENSOR-SPEC §1, eq 9.4)
[[nodiscard]] double timeout_range_m(const RangeCounterParams& p);
// counter = round(range / Δ), clamped to the timeout (SENSOR-SPEC §1 decision); NaN → timeout.
[[nodiscard]] std::uint16_t counter_from_range(double range_m, const RangeCounterParams& p);
// The clamping half of counter_from_range: range/Δ rounded, then into 0..timeout.
[[nodiscard]] inline std::uint16_t counter_from_counts(double counts, std::uint16_t timeout_counts) {
  counts = round_half_away(counts);
  if (!(counts < timeout_counts)) return timeout_counts;  // also catches NaN
  if (counts <= 0.0) return 0;
  return static_cast<std::uint16_t>(counts);
}
// The range a counter stands for: counter · Δ  (SENSOR-SPEC §1)
[[nodiscard]] double range_from_counter(std::uint16_t counter, const RangeCounterParams& p);

// counter_from_range for many ranges with Δ's reciprocal derived once: a multiplication where
// the function divides, and the division itself only for a product within 1e-9 counts of a
// rounding boundary (the product is off the quotient by ~1e-12 counts below 2^13), so every
// counter is counter_from_range's bit for bit. The receiver's per-pulse path: the division was
// its longest latency.
class RangeCounter {
 public:
  explicit RangeCounter(const RangeCounterParams& p)
      : per_count_m_(range_per_count_m(p)),
        counts_per_m_(1.0 / per_count_m_),
        timeout_counts_(p.timeout_counts) {}

  [[nodiscard]] std::uint16_t counter(double range_m) const {
    double counts = range_m * counts_per_m_;
    const double magnitude = std::abs(counts);
    if (magnitude < 0x1p52) {  // NaN, infinities and huge counts are clamped below as they are
      const double fraction = magnitude - static_cast<double>(static_cast<std::int64_t>(magnitude));
      if (std::abs(fraction - 0.5) < 1e-9) counts = range_m / per_count_m_;
    }
    return counter_from_counts(counts, timeout_counts_);
  }

 private:
  double per_count_m_;
  double counts_per_m_;
  std::uint16_t timeout_counts_;
};

}  // namespace owsim
