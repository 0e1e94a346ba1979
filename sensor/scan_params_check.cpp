#include "sensor/scan_params_check.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "sensor/motor_encoder.hpp"

namespace owsim {
namespace {

void require_positive(std::string_view key, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw input_error(key, "must be a finite number > 0, got " + number_text(value));
  }
}

void require_non_negative(std::string_view key, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw input_error(key, "must be a finite number ≥ 0, got " + number_text(value));
  }
}

void check_alpha_table(const ScanParams& p) {
  if (p.alpha_table_deg.empty()) return;
  const auto expected = static_cast<std::size_t>(p.fibers_per_line - 1);
  if (p.alpha_table_deg.size() != expected) {
    throw input_error("sensor.alpha_table_deg",
                      "holds " + std::to_string(p.alpha_table_deg.size()) +
                          " angles, but fibers 1.." + std::to_string(expected) + " need " +
                          std::to_string(expected));
  }
  for (std::size_t i = 0; i < expected; ++i) {
    const double alpha = p.alpha_table_deg[i];
    if (!(std::isfinite(alpha) && std::abs(alpha) <= 90.0)) {
      throw input_error("sensor.alpha_table_deg", "fiber " + std::to_string(i + 1) + " has α " +
                                                      number_text(alpha) + "°, outside −90°..90°");
    }
  }
}

}  // namespace

void validate(const ScanParams& p) {
  require_positive("sensor.prf_hz", p.prf_hz);
  if (p.fibers_per_line < 2) {
    throw input_error(
        "sensor.fibers_per_line",
        "must be ≥ 2 (the last fiber is the reference), got " + std::to_string(p.fibers_per_line));
  }
  if (p.lines_per_frame < 1) {
    throw input_error("sensor.lines_per_frame",
                      "must be ≥ 1, got " + std::to_string(p.lines_per_frame));
  }
  // A frame is simulated as one block in memory (a few hundred bytes a pulse on each thread):
  // 2^20 pulses, 50 times the real sensor's 20,352, keep it within a few hundred MB.
  constexpr long long kMaxPulsesPerFrame = 1 << 20;
  if (static_cast<long long>(p.fibers_per_line) * p.lines_per_frame > kMaxPulsesPerFrame) {
    throw input_error(
        "sensor.lines_per_frame",
        "fibers_per_line × lines_per_frame = " +
            std::to_string(static_cast<long long>(p.fibers_per_line) * p.lines_per_frame) +
            " pulses per frame, more than " + std::to_string(kMaxPulsesPerFrame));
  }
  require_positive("sensor.sweep_deg", p.sweep_deg);
  require_non_negative("sensor.frame_jitter_deg", p.frame_jitter_deg);
  if (0.5 * p.sweep_deg + p.frame_jitter_deg > kMirrorBetaLimitDeg) {
    throw input_error("sensor.sweep_deg", "a sweep of " + number_text(p.sweep_deg) + "° with ±" +
                                              number_text(p.frame_jitter_deg) +
                                              "° jitter leaves the mirror's ±" +
                                              number_text(kMirrorBetaLimitDeg) + "°");
  }
  require_non_negative("sensor.sawtooth_deg", p.sawtooth_deg);
  require_non_negative("sensor.look_into_turn_s", p.look_into_turn_s);
  require_non_negative("sensor.look_into_turn_limit_deg", p.look_into_turn_limit_deg);
  check_alpha_table(p);
  require_non_negative("sensor.hellas_mirror_angle_factor_deg", p.hellas_mirror_angle_factor_deg);
  if (!std::isfinite(p.start_s)) {
    throw input_error("sensor.start_s", "must be a finite number, got " + number_text(p.start_s));
  }
  if (p.reference_counts > kCounterMax) {
    throw input_error("sensor.reference_counts", "must fit the 12-bit counter (≤ 4095), got " +
                                                     std::to_string(p.reference_counts));
  }
  require_positive("sensor.speed_of_light_mps", p.counter.speed_of_light_mps);
  require_positive("sensor.refractive_index_air", p.counter.refractive_index_air);
  require_positive("sensor.timer_period_s", p.counter.timer_period_s);
  if (p.counter.timeout_counts < 1 || p.counter.timeout_counts > kCounterMax) {
    throw input_error("sensor.timeout_counts", "must be 1..4095 (12-bit counter), got " +
                                                   std::to_string(p.counter.timeout_counts));
  }
}

}  // namespace owsim
