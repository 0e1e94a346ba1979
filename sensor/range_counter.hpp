#pragma once
// The range counter (SENSOR-SPEC §1): a 250 MHz timer, 12 bits wide, one tick = 0.59940 m of
// range, 2066 ticks = timeout (no return). Valid for ranges 0..timeout; the counter saturates.
#include <cstdint>

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
// The range a counter stands for: counter · Δ  (SENSOR-SPEC §1)
[[nodiscard]] double range_from_counter(std::uint16_t counter, const RangeCounterParams& p);

}  // namespace owsim
