#include "sensor/range_counter.hpp"

#include <cmath>

#include "geometry/exact_round.hpp"

namespace owsim {

double range_per_count_m(const RangeCounterParams& p) {
  return p.speed_of_light_mps * p.timer_period_s / (2.0 * p.refractive_index_air);
}

double default_range_noise_sigma_m(const RangeCounterParams& p) {
  return range_per_count_m(p) / std::sqrt(2.0);
}

double timeout_range_m(const RangeCounterParams& p) {
  return p.timeout_counts * range_per_count_m(p);
}

std::uint16_t counter_from_range(double range_m, const RangeCounterParams& p) {
  const double counts = round_half_away(range_m / range_per_count_m(p));
  if (!(counts < p.timeout_counts)) return p.timeout_counts;  // also catches NaN
  if (counts <= 0.0) return 0;
  return static_cast<std::uint16_t>(counts);
}

double range_from_counter(std::uint16_t counter, const RangeCounterParams& p) {
  return counter * range_per_count_m(p);
}

}  // namespace owsim
