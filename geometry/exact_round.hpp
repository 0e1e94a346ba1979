#pragma once
// std::round and std::floor without the library call: the baseline x86-64 target (SSE2) has no
// rounding instruction, so std::round and std::lround are calls into libm — several nanoseconds
// each on paths that run once a pulse (range counter, encoder word, time tags).
#include <cmath>
#include <cstdint>

namespace owsim {

// The integer nearest x, halves away from zero: std::round(x) bit for bit, sign of zero and
// NaN included. |x| ≥ 2⁵² is already an integer (or inf/NaN) and comes back as it is.
// No branch on the fraction: it is as likely below a half as above (range counters, encoder
// words), and a mispredicted branch there cost more than the rest of the rounding.
[[nodiscard]] inline double round_half_away(double x) {
  const double magnitude = std::abs(x);
  if (!(magnitude < 0x1p52)) return x;
  const auto truncated = static_cast<double>(static_cast<std::int64_t>(magnitude));
  const double up = static_cast<double>(magnitude - truncated >= 0.5);  // fraction exact; 0 or 1
  return std::copysign(truncated + up, x);
}

// std::round(x) bit for bit where |x| < 2⁵², in double arithmetic alone, without a branch or a
// conversion, so that a loop over an array runs on vector lanes (the ray build's encoder words):
// |x| + 2⁵² − 2⁵² is |x| to the nearest, ties to even (the sum's one rounding), and a tie it took
// down is taken up. |x| ≥ 2⁵² (and inf, NaN) give no rounding the caller may use.
[[nodiscard]] inline double round_half_away_in_lanes(double x) {
  const double magnitude = std::abs(x);
  const double nearest_even = (magnitude + 0x1p52) - 0x1p52;
  const double up = magnitude - nearest_even >= 0.5 ? 1.0 : 0.0;  // the difference is exact
  return std::copysign(nearest_even + up, x);
}

// The largest integer ≤ x: std::floor(x) bit for bit, as round_half_away is std::round's.
[[nodiscard]] inline double round_down(double x) {
  if (!(std::abs(x) < 0x1p52)) return x;
  const auto truncated = static_cast<double>(static_cast<std::int64_t>(x));
  return std::copysign(x < truncated ? truncated - 1.0 : truncated, x);
}

}  // namespace owsim
