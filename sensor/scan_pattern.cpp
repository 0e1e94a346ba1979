#include "sensor/scan_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/error.hpp"
#include "geometry/exact_round.hpp"
#include "geometry/keyed_random.hpp"
#include "sensor/fiber_layout.hpp"

namespace owsim {
namespace {

// How far the sweep centre may move before the jittered sweep leaves the ±30° mechanical range.
double centre_envelope_deg(const ScanParams& p) {
  return std::max(0.0, kMirrorBetaLimitDeg - 0.5 * p.sweep_deg - p.frame_jitter_deg);
}

}  // namespace

double pulse_time_s(const ScanParams& p, std::int64_t frame, int pulse) {
  std::int64_t index = 0;
  if (__builtin_mul_overflow(frame, static_cast<std::int64_t>(p.pulses_per_frame()), &index) ||
      __builtin_add_overflow(index, static_cast<std::int64_t>(pulse), &index)) {
    throw Error("frame " + std::to_string(frame) + " is too far from frame 0 to be timed");
  }
  return p.start_s + static_cast<double>(index) / p.prf_hz;
}

double look_into_turn_shift_deg(const ScanParams& p, double heading_rate_deg_per_s) {
  if (!std::isfinite(heading_rate_deg_per_s)) {
    throw Error("look into turn: the heading rate is not finite");
  }
  if (p.model == SensorModel::hellas || p.look_into_turn_s == 0.0) return 0.0;
  const double limit = std::min(p.look_into_turn_limit_deg, centre_envelope_deg(p));
  return std::clamp(p.look_into_turn_s * heading_rate_deg_per_s, -limit, limit);
}

FrameSweep frame_sweep(const ScanParams& p, std::uint64_t seed, std::int64_t frame,
                       double centre_shift_deg) {
  if (!std::isfinite(centre_shift_deg)) throw Error("frame sweep: centre shift is not finite");
  FrameSweep sweep;
  sweep.frame = frame;
  sweep.direction = (frame & 1) == 0 ? 1 : -1;
  const double envelope = centre_envelope_deg(p);
  sweep.centre_shift_deg = std::clamp(centre_shift_deg, -envelope, envelope);
  const double jitter =
      uniform_pm1(RandomKey{seed, frame, 0, RandomPurpose::frame_jitter}) * p.frame_jitter_deg;
  sweep.mirror_beta_start_deg =
      sweep.centre_shift_deg - 0.5 * p.sweep_deg * sweep.direction + jitter;
  sweep.start_s = pulse_time_s(p, frame, 0);
  return sweep;
}

double mirror_beta_deg(const ScanParams& p, const FrameSweep& sweep, int pulse) {
  return sweep.mirror_beta_start_deg + sweep.direction * p.sweep_deg * pulse / p.pulses_per_frame();
}

Pulse pulse_of_frame(const ScanParams& p, const FrameSweep& sweep, int pulse) {
  const int pulses = p.pulses_per_frame();
  if (pulse < 0 || pulse >= pulses) {
    throw Error("pulse " + std::to_string(pulse) + " is outside the frame 0.." +
                std::to_string(pulses - 1));
  }
  Pulse out;
  out.index = pulse;
  out.line = pulse / p.fibers_per_line;
  out.slot = pulse % p.fibers_per_line;
  out.fiber = fiber_at_slot(p, out.slot);
  out.reference = is_reference_fiber(p, out.fiber);
  out.time_s = pulse_time_s(p, sweep.frame, pulse);
  out.alpha_deg = fiber_alpha_deg(p, out.fiber);
  out.mirror_beta_deg = mirror_beta_deg(p, sweep, pulse);
  out.beta_deg = out.mirror_beta_deg + sawtooth_deg(p, out.fiber);
  out.encoder = p.model == SensorModel::milows ? encoder_from_mirror_beta(out.mirror_beta_deg) : 0;
  out.frame_gate = pulse == pulses - 1;
  out.line_gate = out.slot == p.fibers_per_line - 1;
  out.mov_dir = sweep.direction > 0 ? 0 : 1;
  return out;
}

std::uint16_t time_tag_beyond(double t_s, double whole_ticks, std::uint32_t modulus) {
  if (!std::isfinite(t_s)) throw Error("time tag: pulse time is not finite");
  double wrapped = std::fmod(whole_ticks, static_cast<double>(modulus));  // exact for any double
  if (wrapped < 0.0) wrapped += modulus;
  return static_cast<std::uint16_t>(wrapped);
}

}  // namespace owsim
