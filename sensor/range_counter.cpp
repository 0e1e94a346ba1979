#include "sensor/range_counter.hpp"

#include <cmath>

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
  return counter_from_counts(range_m / range_per_count_m(p), p.timeout_counts);
}

double range_from_counter(std::uint16_t counter, const RangeCounterParams& p) {
  return counter * range_per_count_m(p);
}

}  // namespace owsim
