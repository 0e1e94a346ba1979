#pragma once
// The HELLAS way of telling β (SENSOR-SPEC §8 "Pinned HELLAS details", source eq 4.3): HELLAS has
// no motor encoder; a decoder counts pulses from the NI mark (the one pulse of a frame whose
// mirror β is nearest 0) and multiplies by the mirror angle factor MAF. Ain is a square wave that
// toggles at every line gate; the file's header word holds the mirror β before the first pulse.
//
// With the default MAF (sweep / pulses_per_frame, the true mirror step) the reconstruction
// β[k] = MovDir-sign · (k − k_NI) · MAF is within MAF/2 (0.000884°) of the simulated mirror β.
// The header code holds β in 0.01° steps over −20.48°..+20.47° (12 bits).
#include <cstdint>

#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

inline constexpr double kHellasHeaderBetaOffsetDeg = 20.48;  // §8 header word: β + 20.48°
inline constexpr double kHellasHeaderBetaStepDeg = 0.01;     // §8 header word: 0.01° per code
inline constexpr std::uint16_t kHellasHeaderCodeMax = 4095;  // §8 header word: bits 0–11

// MAF in degrees per pulse: ScanParams::hellas_mirror_angle_factor_deg, or sweep / pulses_per_frame
// when that is 0 (36° / 20,352)  (SENSOR-SPEC §8, eq 4.3)
[[nodiscard]] double hellas_mirror_angle_factor_deg(const ScanParams& p);

// The NI pulse of a frame: the one whose mirror β is nearest 0 (the lower index on a tie);
// −1 when β = 0 lies outside the frame's sweep widened by MAF/2  (SENSOR-SPEC §8 pinned NI)
[[nodiscard]] int hellas_ni_pulse(const ScanParams& p, const FrameSweep& sweep);

// Mirror β a HELLAS decoder reconstructs: direction · (pulse − ni_pulse) · MAF  (SENSOR-SPEC §8,
// eq 4.3) direction +1 for MovDir 0, −1 for MovDir 1. Add sawtooth_deg() for the ray's β.
[[nodiscard]] double hellas_mirror_beta_deg(const ScanParams& p, int pulse, int ni_pulse,
                                            int direction);

// Ain: (global line index frame · lines_per_frame + line) & 1, a square wave that toggles at every
// line gate and runs on across frame boundaries  (SENSOR-SPEC §8 pinned Ain)
[[nodiscard]] bool hellas_ain(const ScanParams& p, std::int64_t frame, int pulse);

// Header word code round((β + 20.48°) / 0.01°), clamped to 0..4095  (SENSOR-SPEC §8 header word)
// Throws owsim::Error for a non-finite β.
[[nodiscard]] std::uint16_t hellas_header_beta_code(double beta_start_deg);
// The β a header code stands for: code · 0.01° − 20.48°  (SENSOR-SPEC §8 header word)
[[nodiscard]] double hellas_beta_from_header_code(std::uint16_t code);

}  // namespace owsim
