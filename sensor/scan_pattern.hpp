#pragma once
// The MilOWS/HELLAS scan pattern as a pure function of (frame, pulse) (SENSOR-SPEC §2, §3, §8):
// when each pulse fires, which fiber it uses, its α and β, the encoder word and the gate flags.
//
// Pinned timing and sweep of SENSOR-SPEC §2: pulse k of frame f fires at
// start_s + (f · pulses_per_frame + k) / PRF; the mirror β(k) = β0 + s · sweep · k /
// pulses_per_frame with s = +1 on even frames (MovDir 0) and −1 on odd ones, β0 = shift − s ·
// sweep/2 + U(−1,1) · jitter, the uniform keyed by (seed, frame, frame_jitter). Nothing is a
// running total: any frame can be computed alone and gives the same numbers. Valid for frames with
// |f · pulses_per_frame| < 2^63 and parameters that pass validate(); angles are exact to double
// rounding, times to 1 ulp.
#include <cmath>
#include <cstdint>
#include <span>

#include "geometry/exact_round.hpp"
#include "sensor/motor_encoder.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

inline constexpr double kMilowsTimeTagTickS = 100e-6;          // §8 eq 10.1: 100 µs per tick
inline constexpr std::uint32_t kMilowsTimeTagModulus = 65536;  // §8: u16, cyclic
inline constexpr double kHellasTimeTagTickS = 0.5e-3;          // §8: 0.5 ms per tick
inline constexpr std::uint32_t kHellasTimeTagModulus = 16384;  // §8: 14 bits, cyclic

// The sweep of one frame: everything about it that does not depend on the pulse.
struct FrameSweep {
  std::int64_t frame = 0;
  int direction = 1;                   // +1 on even frames (β rises), −1 on odd frames
  double mirror_beta_start_deg = 0.0;  // β0: mirror β of pulse 0, jitter included
  double centre_shift_deg = 0.0;       // look-into-turn shift of the sweep centre
  double start_s = 0.0;                // time of pulse 0
};

// One pulse of a frame, as the sensor fires and records it.
struct Pulse {
  int index = 0;           // 0..pulses_per_frame−1 within the frame
  int line = 0;            // 0..lines_per_frame−1
  int slot = 0;            // position in the line, 0..fibers_per_line−1
  int fiber = 0;           // 1..fibers_per_line
  bool reference = false;  // the reference fiber: no ray leaves the sensor
  double time_s = 0.0;
  double alpha_deg = 0.0;        // NaN for the reference fiber
  double mirror_beta_deg = 0.0;  // what the encoder sees
  double beta_deg = 0.0;         // the ray's β: mirror β + β_FC
  EncoderCount encoder = 0;      // MilOWS motor encoder word; 0 for HELLAS
  bool frame_gate = false;       // last pulse of the frame (FG; HELLAS BT = !frame_gate)
  bool line_gate = false;        // last pulse of a line (LG; HELLAS ZT = !line_gate)
  int mov_dir = 0;               // 0 while β increases, 1 while it decreases
};

// Time of pulse k of frame f: start_s + (f · pulses_per_frame + k) / PRF  (SENSOR-SPEC §2 pinned
// timing) The index is formed in int64 first; throws owsim::Error if it would overflow.
[[nodiscard]] double pulse_time_s(const ScanParams& p, std::int64_t frame, int pulse);

// Look-into-turn shift of the sweep centre: clamp(τ · ψ̇, ±limit), and no further than keeps the
// jittered sweep inside ±30°; 0 for HELLAS or τ = 0  (SENSOR-SPEC §2 look into turn)
// ψ̇ in deg/s, positive turning right. Throws owsim::Error for a non-finite rate.
[[nodiscard]] double look_into_turn_shift_deg(const ScanParams& p, double heading_rate_deg_per_s);

// The sweep of frame f: direction, β0 = shift − s · sweep/2 + U(−1,1) · jitter, start time
// (SENSOR-SPEC §2 pinned sweep, eq 4.5–4.6). centre_shift_deg (from look_into_turn_shift_deg) is
// clamped to the mechanical ±30° envelope.
[[nodiscard]] FrameSweep frame_sweep(const ScanParams& p, std::uint64_t seed, std::int64_t frame,
                                     double centre_shift_deg = 0.0);

// Mirror β of pulse k: β0 + s · sweep · k / pulses_per_frame  (SENSOR-SPEC §2 pinned sweep)
[[nodiscard]] double mirror_beta_deg(const ScanParams& p, const FrameSweep& sweep, int pulse);

// Everything about pulse k of a frame  (SENSOR-SPEC §2, §3, §8). Throws for k outside the frame.
[[nodiscard]] Pulse pulse_of_frame(const ScanParams& p, const FrameSweep& sweep, int pulse);

// MilOWS time tag floor(t / 100 µs) mod 65,536  (SENSOR-SPEC §8 pinned time tag, eq 10.1)
// and HELLAS floor(t / 0.5 ms) mod 16,384  (SENSOR-SPEC §8). A time that lies within a relative
// 1e-14 below a tick boundary counts as on it: t = n / PRF rounds to a hair below an exact
// boundary, while the true distance of a pulse below a boundary is at least 1/PRF of a tick
// (1.6e-5), so the result is exact for |t| up to ~1.6e5 s. Throws for a non-finite t.
// Inline: the word packing takes one a pulse. The common case (|ticks| < 2⁶²) masks the int64
// tick count, the floored modulo of both power-of-two ranges; the rest (huge and non-finite
// times) goes to time_tag_beyond, which wraps with fmod or throws.
[[nodiscard]] std::uint16_t time_tag_beyond(double t_s, double whole_ticks, std::uint32_t modulus);
template <std::uint32_t Modulus>
[[nodiscard]] inline std::uint16_t time_tag(double t_s, double ticks_per_s) {
  static_assert(Modulus != 0 && (Modulus & (Modulus - 1)) == 0 && Modulus <= 65536);
  const double ticks = t_s * ticks_per_s;
  const double whole = round_down(ticks + std::abs(ticks) * 1e-14);
  if (!(std::abs(whole) < 0x1p62)) return time_tag_beyond(t_s, whole, Modulus);  // NaN too
  return static_cast<std::uint16_t>(static_cast<std::int64_t>(whole) &
                                    static_cast<std::int64_t>(Modulus - 1));
}
[[nodiscard]] inline std::uint16_t milows_time_tag(double t_s) {
  return time_tag<kMilowsTimeTagModulus>(t_s, 1.0 / kMilowsTimeTagTickS);
}
// milows_time_tag of each time, over arrays (the same values, vectorised; a time too large for
// the common case, or not finite, goes through milows_time_tag, which wraps or throws).
void milows_time_tags(std::span<const double> times_s, std::span<std::uint16_t> tags);

[[nodiscard]] inline std::uint16_t hellas_time_tag(double t_s) {
  return time_tag<kHellasTimeTagModulus>(t_s, 1.0 / kHellasTimeTagTickS);
}

}  // namespace owsim
