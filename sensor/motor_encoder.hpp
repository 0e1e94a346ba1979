#pragma once
// The MilOWS motor encoder ↔ mirror angle β (SENSOR-SPEC §3, source eq 4.1–4.7 and appendix A).
//
// The mirror is driven through a four-bar linkage; the source fits the motor angle φ as a
// degree-10 polynomial of β (appendix A table 4.1), monotonic (dφ/dβ < 0) over β ∈ [−30°, 30°],
// so its inverse is unique there. The encoder is a 16-bit signed count of 360°/65536.
// Valid range: β ∈ [−30°, 30°]; the inverse is exact to 1e-9° on that range.
#include <array>
#include <cmath>
#include <cstdint>

#include "geometry/exact_round.hpp"

namespace owsim {

using EncoderCount = std::int16_t;

inline constexpr double kEncoderDegPerCount = 360.0 / 65536.0;  // §3 eq 4.7: 0.0054931640625°
inline constexpr double kMirrorBetaLimitDeg = 30.0;             // §2: β stays within ±30°

// bc1..bc11 of appendix A table 4.1: φ(β) = Σ bc_i · β^(11−i), degrees.
inline constexpr std::array<double, 11> kMotorPolynomial = {
    4.6809e-17, -7.6174e-15, 2.806e-14, -1.1676e-11, 3.2275e-11, -3.6118e-8,
    -1.2932e-7, -0.00013677, -0.0017148, -1.5399, -115.91};

// Motor angle φ(β) in degrees  (SENSOR-SPEC §3, appendix A table 4.1)
// Estrin's scheme: four dependent multiply-adds instead of Horner's ten (it runs per pulse, and
// inline it vectorises over a line's pulses). Over ±30° it agrees with Horner's to 3e-14°, 5e-12
// of an encoder count.
[[nodiscard]] inline double motor_angle_deg(double mirror_beta_deg) {
  const auto& c = kMotorPolynomial;  // c[0] multiplies β^10
  const double x = mirror_beta_deg, x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  const double low = (c[10] + c[9] * x) + (c[8] + c[7] * x) * x2 +
                     ((c[6] + c[5] * x) + (c[4] + c[3] * x) * x2) * x4;
  const double high = (c[2] + c[1] * x) + c[0] * x2;
  return low + high * x8;
}
// dφ/dβ, used by the inverse  (SENSOR-SPEC §3)
[[nodiscard]] double motor_angle_slope(double mirror_beta_deg);
// β(φ): the inverse polynomial, Newton safeguarded by bisection on [−30°, 30°]  (SENSOR-SPEC §3)
// φ outside [φ(30°), φ(−30°)] is clamped to the nearest end of the valid range.
[[nodiscard]] double mirror_beta_deg_from_motor_angle(double motor_angle_deg);
// The encoder word of φ in counts (φ / 0.0054931640625°): the nearest count, halves away from
// zero, as int16 (wrapping like the 16-bit word)  (SENSOR-SPEC §3, eq 4.7) Inline, without a
// libm call: it runs once a pulse. NaN and |counts| ≥ 2⁶³ give 0, as lround's LONG_MIN
// would.
[[nodiscard]] inline EncoderCount encoder_word(double counts) {
  const double nearest = round_half_away(counts);
  if (!(std::abs(nearest) < 0x1p63)) return 0;
  return static_cast<EncoderCount>(static_cast<std::int64_t>(nearest));
}
// encoder_word(counts) from the rounding a loop over an array made on vector lanes,
// `rounded` = round_half_away_in_lanes(counts): through int32 for every count of the mirror's
// ±30° (|counts| < 2³⁰), by encoder_word itself beyond.
[[nodiscard]] inline EncoderCount encoder_word(double counts, double rounded) {
  if (!(std::abs(counts) < 0x1p30)) return encoder_word(counts);
  return static_cast<EncoderCount>(static_cast<std::int32_t>(rounded));
}
// Encoder word value round(φ / 0.0054931640625°) as int16  (SENSOR-SPEC §3, eq 4.7)
[[nodiscard]] inline EncoderCount encoder_count(double motor_angle_deg) {
  return encoder_word(motor_angle_deg / kEncoderDegPerCount);
}
// The motor angle an encoder count stands for  (SENSOR-SPEC §3, eq 4.7)
[[nodiscard]] double motor_angle_from_encoder_deg(EncoderCount count);
// Mirror β → encoder word, and back (via the inverse polynomial)  (SENSOR-SPEC §3)
[[nodiscard]] EncoderCount encoder_from_mirror_beta(double mirror_beta_deg);
[[nodiscard]] double mirror_beta_deg_from_encoder(EncoderCount count);

}  // namespace owsim
