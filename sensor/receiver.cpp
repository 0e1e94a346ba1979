#include "sensor/receiver.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "geometry/error.hpp"
#include "geometry/keyed_random.hpp"
#include "geometry/number_text.hpp"
#include "geometry/scene.hpp"
#include "sensor/footprint.hpp"
#include "sensor/return_energy.hpp"

namespace owsim {
namespace {

void require_non_negative(std::string_view key, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw input_error(key, "must be a finite number ≥ 0, got " + number_text(value));
  }
}

void require_positive(std::string_view key, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw input_error(key, "must be a finite number > 0, got " + number_text(value));
  }
}

// Range order; equal ranges by higher energy, then object and surface, so the order is total.
bool nearer(const Candidate& a, const Candidate& b) {
  if (a.range_m != b.range_m) return a.range_m < b.range_m;
  if (a.energy_rel != b.energy_rel) return a.energy_rel > b.energy_rel;
  if (a.object_index != b.object_index) return a.object_index < b.object_index;
  return a.surface < b.surface;
}

bool stronger(const Candidate& a, const Candidate& b) {
  if (a.energy_rel != b.energy_rel) return a.energy_rel > b.energy_rel;
  return nearer(a, b);
}

// The range plus σ times a standard normal (σ = 0: the range itself, the normal unread).
double noisy_range_m(double range_m, double sigma_m, double normal) {
  return sigma_m == 0.0 ? range_m : range_m + sigma_m * normal;
}

}  // namespace

void validate(const ReceiverParams& p) {
  if (!(std::isfinite(p.beam.divergence_mrad) && p.beam.divergence_mrad >= 0.0 &&
        p.beam.divergence_mrad < 1000.0)) {
    throw input_error("sensor.divergence_mrad", "must be a full angle in [0, 1000) mrad, got " +
                                                    number_text(p.beam.divergence_mrad));
  }
  require_non_negative("sensor.beam_exit_radius_m", p.beam.exit_radius_m);
  if (!(p.threshold >= 0.0 && p.threshold <= 1.0)) {
    throw input_error("sensor.threshold",
                      "must be an energy ratio in [0, 1], got " + number_text(p.threshold));
  }
  if (!std::isfinite(p.range_noise_sigma_m)) {
    throw input_error("sensor.range_noise_sigma_m",
                      "must be a finite number (0 disables, negative = Δ/√2), got " +
                          number_text(p.range_noise_sigma_m));
  }
  require_non_negative("sensor.min_return_separation_m", p.min_return_separation_m);
  validate(p.atmosphere);
  require_positive("sensor.speed_of_light_mps", p.counter.speed_of_light_mps);
  require_positive("sensor.refractive_index_air", p.counter.refractive_index_air);
  require_positive("sensor.timer_period_s", p.counter.timer_period_s);
  if (p.counter.timeout_counts < 1 || p.counter.timeout_counts > kCounterMax) {
    throw input_error("sensor.timeout_counts", "must be 1..4095 (12-bit counter), got " +
                                                   std::to_string(p.counter.timeout_counts));
  }
  require_non_negative("sensor.receiver.noise_at_1km", p.noise.noise_at_1km);
  require_positive("sensor.receiver.pulse_width_ns", p.noise.pulse_width_ns);
  require_non_negative("sensor.receiver.sun_noise", p.noise.sun_noise);
  require_non_negative("sensor.receiver.sky_noise", p.noise.sky_noise);
  if (p.sun.given && !(std::abs(p.sun.elevation_deg) <= 90.0)) {
    throw input_error("sun.elevation_deg",
                      "must be in [-90, 90] deg, got " + number_text(p.sun.elevation_deg));
  }
  if (p.sun.given && !std::isfinite(p.sun.azimuth_deg)) {
    throw input_error("sun.azimuth_deg", "must be a finite angle clockwise from north, got " +
                                             number_text(p.sun.azimuth_deg));
  }
}

ReceiverNoise receiver_noise(const ReceiverParams& p) {
  return ReceiverNoise(p.noise, p.sun, p.threshold, timeout_range_m(p.counter),
                       p.counter.speed_of_light_mps / p.counter.refractive_index_air);
}

double range_noise_sigma_m(const ReceiverParams& p) {
  return p.range_noise_sigma_m < 0.0 ? default_range_noise_sigma_m(p.counter)
                                     : p.range_noise_sigma_m;
}

namespace {

// SENSOR-SPEC §7 detection: ξ_rx/ξ_tx ≥ threshold (NaN energies and ranges never register).
bool registers(const Candidate& c, const ReceiverParams& p) {
  return c.energy_rel >= p.threshold && std::isfinite(c.range_m);
}

// SENSOR-SPEC §1 noise and counter for the chosen candidates (chosen[1] may be null), written
// into `out` whose count is 0 and counters the timeout; a counter at the timeout is no return.
void record_returns(const Candidate* const (&chosen)[2], const ReceiverParams& p,
                    std::uint64_t seed, std::int64_t frame, int pulse, PulseReturns& out,
                    const PhiloxBlock* first_range_noise) {
  const double sigma = range_noise_sigma_m(p);
  const RangeCounter counters(p.counter);
  constexpr RandomPurpose kPurpose[2] = {RandomPurpose::range_noise_first,
                                         RandomPurpose::range_noise_second};
  for (int i = 0; i < 2 && chosen[i] != nullptr; ++i) {
    const Candidate& c = *chosen[i];
    const RandomKey key{seed, frame, pulse, kPurpose[i]};
    const double normal = sigma == 0.0 ? 0.0
                          : i == 0 && first_range_noise != nullptr
                              ? standard_normal(key, *first_range_noise)
                              : standard_normal(key);
    const double range = noisy_range_m(c.range_m, sigma, normal);
    const std::uint16_t counter = counters.counter(range);
    if (counter >= p.counter.timeout_counts) continue;
    out.returns[out.count++] = return_of(c, std::max(range, 0.0), counter);
  }
  if (out.count == 2 && out.returns[1].range_m < out.returns[0].range_m) {
    std::swap(out.returns[0], out.returns[1]);
  }
  if (out.count >= 1) out.counter1 = out.returns[0].counter;
  if (out.count == 2) out.counter2 = out.returns[1].counter;
}

}  // namespace

namespace {

// SENSOR-SPEC §7 pinned return selection over candidates that all registered (sorted in place).
void choose_returns(std::span<Candidate> detected, const ReceiverParams& p,
                    const Candidate* (&chosen)[2]) {
  if (p.rule == ReturnRule::strongest) {
    chosen[0] = &*std::min_element(detected.begin(), detected.end(), stronger);
    return;
  }
  std::sort(detected.begin(), detected.end(), nearer);
  chosen[0] = &detected.front();
  for (const Candidate& c : detected.subspan(1)) {
    if (c.range_m >= detected.front().range_m + p.min_return_separation_m) {
      chosen[1] = &c;
      return;
    }
  }
}

// A false trigger at `range_m`: it crossed the threshold there, no object, no incidence
// (SENSOR-SPEC §11 returns).
Candidate false_return(double range_m, const ReceiverParams& p) {
  return Candidate{range_m, p.threshold, std::numeric_limits<double>::quiet_NaN(), kNoObject,
                   static_cast<std::uint8_t>(SurfaceClass::noise)};
}

// SENSOR-SPEC §11 returns: the echoes that register through the noise (moved to the front of
// `candidates`) and the pulse's false triggers, in range order, then §7's selection. Only the
// triggers that can become a return are drawn: the nearest, and (first_second) the nearest one a
// separation beyond the first return — the Poisson process beyond a point is independent of what
// lies before it. Most pulses draw no trigger and select among their echoes in place.
void select_noisy_returns(std::span<Candidate> candidates, const ReceiverParams& p,
                          std::uint64_t seed, std::int64_t frame, int pulse,
                          const PulseNoise& noise, PulseReturns& out) {
  set_no_returns(p, out);
  const ReceiverNoise& model = *noise.model;
  // Most pulses that meet nothing: no false trigger in their whole group (the first test below).
  if (candidates.empty() && model.group_has_no_trigger(noise.background, seed, frame, pulse))
    return;
  const std::span<Candidate> registered(
      candidates.begin(),
      std::partition(candidates.begin(), candidates.end(), [&](const Candidate& c) {
        return model.echo_registers(c.energy_rel, c.range_m, noise.background, seed, frame, pulse,
                                    c.object_index);
      }));
  std::uint32_t draw = 0;
  const double trigger =
      model.next_false_trigger_m(0.0, noise.background, noise.busy, seed, frame, pulse, draw);
  const Candidate* chosen[2] = {nullptr, nullptr};
  if (trigger < 0.0) {
    if (registered.empty()) return;
    if (registered.size() == 1) {
      chosen[0] = &registered.front();
    } else {
      choose_returns(registered, p, chosen);
    }
    record_returns(chosen, p, seed, frame, pulse, out, noise.first_range_noise);
    return;
  }
  std::array<Candidate, kMaxNoisyCandidates + 2> pool;
  const std::size_t echoes = std::min(registered.size(), kMaxNoisyCandidates);
  std::copy_n(registered.begin(), echoes, pool.begin());
  std::size_t n = echoes;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < echoes; ++i) nearest = std::min(nearest, pool[i].range_m);
  pool[n++] = false_return(trigger, p);
  const double second_from = std::min(nearest, trigger) + p.min_return_separation_m;
  if (p.rule == ReturnRule::first_second && trigger < second_from) {
    const double second = model.next_false_trigger_m(second_from, noise.background, noise.busy,
                                                     seed, frame, pulse, draw);
    if (second >= 0.0) pool[n++] = false_return(second, p);
  }
  choose_returns(std::span<Candidate>(pool.data(), n), p, chosen);
  record_returns(chosen, p, seed, frame, pulse, out, noise.first_range_noise);
}

bool noisy(const PulseNoise& noise) { return noise.model != nullptr && noise.model->on(); }

}  // namespace

void select_returns(std::span<Candidate> candidates, const ReceiverParams& p, std::uint64_t seed,
                    std::int64_t frame, int pulse, PulseReturns& out, const PulseNoise& noise) {
  if (noisy(noise)) {
    select_noisy_returns(candidates, p, seed, frame, pulse, noise, out);
    return;
  }
  if (candidates.size() == 1) {
    select_single_return(candidates.front(), p, seed, frame, pulse, out);
    return;
  }
  set_no_returns(p, out);
  if (candidates.empty()) return;
  if (candidates.size() == 2 && p.rule == ReturnRule::first_second) {
    // Two candidates (a fog echo and what lies behind it, a wire and the ground): no sorting.
    const Candidate& a = candidates[0];
    const Candidate& b = candidates[1];
    const bool a_in = registers(a, p);
    const bool b_in = registers(b, p);
    const Candidate* chosen[2] = {nullptr, nullptr};
    if (a_in && b_in) {
      const Candidate& first = nearer(a, b) ? a : b;
      const Candidate& second = &first == &a ? b : a;
      chosen[0] = &first;
      if (second.range_m >= first.range_m + p.min_return_separation_m) chosen[1] = &second;
    } else if (a_in || b_in) {
      chosen[0] = a_in ? &a : &b;
    }
    if (chosen[0] != nullptr)
      record_returns(chosen, p, seed, frame, pulse, out, noise.first_range_noise);
    return;
  }
  // SENSOR-SPEC §7 pinned return selection.
  const std::span<Candidate> detected(
      candidates.begin(), std::partition(candidates.begin(), candidates.end(),
                                         [&](const Candidate& c) { return registers(c, p); }));
  if (detected.empty()) return;
  const Candidate* chosen[2] = {nullptr, nullptr};
  choose_returns(detected, p, chosen);
  record_returns(chosen, p, seed, frame, pulse, out, noise.first_range_noise);
}

void select_single_return(const Candidate& candidate, const ReceiverParams& p, std::uint64_t seed,
                          std::int64_t frame, int pulse, PulseReturns& out,
                          const PulseNoise& noise) {
  if (noisy(noise)) {
    // Most pulses: no false trigger in the pulse's whole group (select_noisy_returns' first test),
    // so the echo alone decides — without the general path's pool and trigger search.
    if (noise.model->group_has_no_trigger(noise.background, seed, frame, pulse)) {
      set_no_returns(p, out);
      if (!noise.model->echo_registers(candidate.energy_rel, candidate.range_m, noise.background,
                                       seed, frame, pulse, candidate.object_index)) {
        return;
      }
      const Candidate* const chosen[2] = {&candidate, nullptr};
      record_returns(chosen, p, seed, frame, pulse, out, noise.first_range_noise);
      return;
    }
    Candidate copy = candidate;
    select_noisy_returns(std::span<Candidate>(&copy, 1), p, seed, frame, pulse, noise, out);
    return;
  }
  set_no_returns(p, out);
  // One surface: nothing to sort; either rule keeps it if it registers.
  if (!registers(candidate, p)) return;
  const Candidate* const chosen[2] = {&candidate, nullptr};
  record_returns(chosen, p, seed, frame, pulse, out, noise.first_range_noise);
}

std::uint16_t reference_counter(std::uint16_t reference_counts, const ReceiverParams& p,
                                std::uint64_t seed, std::int64_t frame, int pulse) {
  const double sigma = range_noise_sigma_m(p);
  const double normal =
      sigma == 0.0 ? 0.0
                   : standard_normal({seed, frame, pulse, RandomPurpose::range_noise_reference});
  return counter_from_range(
      noisy_range_m(range_from_counter(reference_counts, p.counter), sigma, normal), p.counter);
}

double max_detection_range_m(double wire_diameter_m, double reflectivity, const ReceiverParams& p) {
  const double wire_radius = 0.5 * wire_diameter_m;
  const auto detected = [&](double range_m) {
    const double fraction = footprint_fraction(0.0, wire_radius, beam_radius_m(range_m, p.beam));
    const double energy =
        energy_rel(fraction, 0.0, reflectivity, two_way_transmission(p.atmosphere, range_m));
    return energy >= p.threshold;
  };
  double near = 0.0;
  double far = timeout_range_m(p.counter);
  if (detected(far)) return far;
  if (!detected(near)) return 0.0;
  // Energy falls monotonically with range (the beam widens, T_atm falls): bisect the crossing.
  for (int iteration = 0; iteration < 200 && far - near > 1e-9 * far; ++iteration) {
    const double middle = 0.5 * (near + far);
    (detected(middle) ? near : far) = middle;
  }
  return near;
}

}  // namespace owsim
