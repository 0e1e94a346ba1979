#pragma once
// The MilOWS receiver (SENSOR-SPEC §1 and §7): detection threshold, return selection, range noise
// and the range counter, for one pulse at a time.
//
// The engine hands select_returns() every candidate a pulse's beam met (wires by closest approach,
// poles, trees and ground by the central ray's hit, each with its energy from
// sensor/return_energy.hpp, occluded wires already dropped). The receiver keeps candidates with
// energy_rel ≥ threshold and picks the returns: `first_second` (default) records the nearest and
// the next one at least min_return_separation_m (0.75 m = c·5 ns/2) beyond it, `strongest` the
// source's single highest-energy return. Each return's range gets Gaussian noise keyed by
// (seed, frame, pulse, return number) — σ = 0.4241 m by default, the §1 table's figure; a
// negative σ means Δ/√2 = 0.42384 m with Δ = 0.59940 m — and becomes a counter round(range/Δ);
// a counter at the timeout (2066) is no return.
// Decisions where the spec is silent: (1) a return whose noisy counter reaches the timeout is
// dropped and a surviving second return moves up to slot 1; (2) after noise the surviving returns
// are ordered by noisy range, so counter 1 ≤ counter 2 always (return 1 is the earlier echo); (3)
// a noisy range below 0 is reported as 0; (4) equal ranges are ordered by higher energy, then
// object index, then surface, so the result never depends on the input order.
// Allocation-free and thread-safe: the candidate span is sorted in place.
#include <cstddef>
#include <cstdint>
#include <span>

#include "geometry/keyed_random.hpp"
#include "sensor/atmosphere.hpp"
#include "sensor/beam.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/receiver_noise.hpp"

namespace owsim {

// Which detected candidates become returns (SENSOR-SPEC §7 pinned return selection).
enum class ReturnRule {
  first_second,  // default: nearest, then the next at least min_return_separation_m beyond it
  strongest,     // the source's rule: the highest-energy candidate only (ties → nearer)
};

struct ReceiverParams {
  BeamParams beam;  // §7
  // §7 minimum ξ_rx/ξ_tx (key sensor.threshold), calibrated with §11's receiver noise
  // (docs/model.md "Receiver statistics"; owsim 0.1.0's deterministic receiver used 0.005)
  double threshold = 0.0029;
  double range_noise_sigma_m =
      0.4241;  // §1 σ; 0 disables, negative → Δ/√2 (key sensor.range_noise_sigma_m)
  ReturnRule rule = ReturnRule::first_second;  // key sensor.returns
  double min_return_separation_m = 0.75;       // §7 c·5 ns/2 (key sensor.min_return_separation_m)
  Atmosphere atmosphere;                       // §7 T_atm
  RangeCounterParams counter;                  // §1
  ReceiverNoiseParams noise;                   // §11 (keys sensor.receiver.*)
  SunPosition sun;                             // §11 sunlight (the scenario's `sun`)
};

// Throws owsim::Error naming the scenario key for: a divergence outside [0, 1000) mrad, a negative
// exit radius, a threshold outside [0, 1], a non-finite noise σ, a negative separation, a bad
// atmosphere (validate(Atmosphere)), non-positive counter constants or a timeout outside 1..4095,
// negative or non-finite receiver-noise keys (SENSOR-SPEC §11), a pulse width ≤ 0, a sun
// elevation outside [−90, 90] or a non-finite azimuth.
// Every field is checked, so the per-pulse functions need not be.
void validate(const ReceiverParams& p);

// The σ in use: range_noise_sigma_m, or Δ/√2 when it is negative  (SENSOR-SPEC §1, eq 3.3)
[[nodiscard]] double range_noise_sigma_m(const ReceiverParams& p);

// One object the beam met on one pulse. `surface` is the caller's surface class (the engine's
// wire / pole / tree / ground tag); the receiver carries it through without reading it.
struct Candidate {
  double range_m = 0.0;        // true range along the ray
  double energy_rel = 0.0;     // ξ_rx / ξ_tx (sensor/return_energy.hpp)
  double incidence_deg = 0.0;  // θ at the object
  std::uint32_t object_index = 0;
  std::uint8_t surface = 0;
};

// Fields ordered largest first: a frame holds one PulseReturns a pulse, written by the receiver
// and read by every output, so its 88 bytes (not 112 with padding) are memory traffic saved.
struct Return {
  double range_m = 0.0;  // after noise
  double energy_rel = 0.0;
  double incidence_deg = 0.0;
  double true_range_m = 0.0;
  std::uint32_t object_index = 0;
  std::uint16_t counter = 0;
  std::uint8_t surface = 0;
};

struct PulseReturns {
  int count = 0;                                                 // valid entries in returns: 0..2
  std::uint16_t counter1 = RangeCounterParams{}.timeout_counts;  // the timeout when absent
  std::uint16_t counter2 = RangeCounterParams{}.timeout_counts;  // the timeout when absent
  Return returns[2];
};

// The return a candidate becomes at its noisy range (≥ 0) and counter: its energy, incidence,
// true range, object and class carried through (SENSOR-SPEC §1, §7).
[[nodiscard]] inline Return return_of(const Candidate& c, double range_m, std::uint16_t counter) {
  return Return{range_m,        c.energy_rel, c.incidence_deg, c.range_m,
                c.object_index, counter,      c.surface};
}

// The receiver's statistics for these parameters: threshold, noise keys, sun, and the gate from 0
// to the counter's timeout range with light at c / n_air  (SENSOR-SPEC §11)
[[nodiscard]] ReceiverNoise receiver_noise(const ReceiverParams& p);

// What the receiver's statistics need of one pulse (SENSOR-SPEC §11). The default — no model —
// is §7's deterministic receiver.
struct PulseNoise {
  const ReceiverNoise* model = nullptr;  // null or off: deterministic, no false trigger
  double background = 0.0;               // b of the pulse (ReceiverNoise::solid/sky_background)
  std::span<const BusyInterval> busy;    // fog busy intervals on the pulse's path, nearest first
  // random_block of the pulse's first-return range noise key (seed, frame, pulse,
  // range_noise_first) when the caller drew it ahead with a block of pulses (random_blocks);
  // null: drawn here. The same normal either way (SENSOR-SPEC §1).
  const PhiloxBlock* first_range_noise = nullptr;
};

// The most candidates select_returns takes with a noise model (every wire, the solid, the fog's).
inline constexpr std::size_t kMaxNoisyCandidates = 22;

// Threshold, selection, noise and counters for one pulse, written into `out`  (SENSOR-SPEC §1,
// §7 pinned return selection). Reorders `candidates` in place; allocation-free. Only
// out.returns[0 .. count) are written: the entries beyond are left as they were. With a noise
// model that is on (SENSOR-SPEC §11) each candidate registers with probability Φ((e − T)/σ_n)
// and the pulse's false triggers join the echoes before §7's selection: a false return is
// class noise, object kNoObject, energy_rel T, incidence NaN.
void select_returns(std::span<Candidate> candidates, const ReceiverParams& p, std::uint64_t seed,
                    std::int64_t frame, int pulse, PulseReturns& out, const PulseNoise& noise = {});
// No return: count 0 and both counters at the timeout (the returns array is left as it was):
// select_returns of no candidate.
inline void set_no_returns(const ReceiverParams& p, PulseReturns& out) {
  out.count = 0;
  out.counter1 = out.counter2 = p.counter.timeout_counts;
}
// select_returns of the one candidate a pulse met (most pulses: one surface, no wire), without
// copying it into a span first.
void select_single_return(const Candidate& candidate, const ReceiverParams& p, std::uint64_t seed,
                          std::int64_t frame, int pulse, PulseReturns& out,
                          const PulseNoise& noise = {});
// The same, returned.
[[nodiscard]] inline PulseReturns select_returns(std::span<Candidate> candidates,
                                                 const ReceiverParams& p, std::uint64_t seed,
                                                 std::int64_t frame, int pulse) {
  PulseReturns out;
  select_returns(candidates, p, seed, frame, pulse, out);
  return out;
}

// Which of a pulse's returns lie on a named scene object — an object index below `named_objects`
// (geometry/scene.hpp named_object_count: the conductors, cylinders and meshes; not the terrain or
// fog): bit r set for returns[r], r = 0, 1. Branch-free: an entry past `count` is masked.
[[nodiscard]] inline std::uint8_t object_return_bits(const PulseReturns& r,
                                                     std::size_t named_objects) {
  const bool first = (r.count >= 1) & (r.returns[0].object_index < named_objects);
  const bool second = (r.count >= 2) & (r.returns[1].object_index < named_objects);
  return static_cast<std::uint8_t>(static_cast<unsigned>(first) |
                                   (static_cast<unsigned>(second) << 1));
}

// The reference fiber's counter: reference_counts·Δ plus the same range noise, keyed
// range_noise_reference  (SENSOR-SPEC §8)
[[nodiscard]] std::uint16_t reference_counter(std::uint16_t reference_counts,
                                              const ReceiverParams& p, std::uint64_t seed,
                                              std::int64_t frame, int pulse);

// The longest range at which a wire of this diameter and reflectivity crossing the beam centre
// head-on (d = 0, θ = 0) still reaches the threshold, by bisection on (0, timeout range]; the
// timeout range when it is detected all the way, 0 when never  (SENSOR-SPEC §7)
[[nodiscard]] double max_detection_range_m(double wire_diameter_m, double reflectivity,
                                           const ReceiverParams& p);

}  // namespace owsim
