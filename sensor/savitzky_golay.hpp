#pragma once
// Savitzky–Golay smoothing of navigation channels (SENSOR-SPEC §5, source ch. 8).
//
// Each sample is replaced by the value at its own time of the least-squares polynomial of
// `degree` through the `window` samples around it (Savitzky & Golay 1964). The source used
// window 5, degree 4 — a degree-4 polynomial through 5 points reproduces them, so that is the
// identity; owsim defaults to window 9, degree 3. Window 1, or degree ≥ window − 1, is the
// identity.
//
// Ends: the first and last window/2 samples take the polynomial fitted over the first (last)
// full window, evaluated at their own times (scipy.signal.savgol_filter mode='interp').
// Sampling: windows are counted in samples, but every fit uses the samples' actual times, so
// uneven steps (a 4 Hz GPS mixed into 10 Hz attitude, a dropped record) are handled exactly:
// a polynomial of the filter's degree is reproduced for any strictly increasing times. On
// uniform steps this is the classical filter (matches scipy to 1e-9, tested); a window that
// straddles a long gap simply spans more time. Fewer samples than the window: the window shrinks to
// the largest odd count available (and the degree to at most that count − 1). Accuracy: double
// precision; abscissae are scaled to [−1, 1] per window before the QR solve.
#include <span>
#include <string_view>
#include <vector>

namespace owsim {

struct SmoothingParams {
  int window = 9;  // samples, odd, ≥ 1 (1 = off)
  int degree = 3;  // polynomial degree, ≥ 0
};

// Throws owsim::Error "<where>: <problem>" unless window is odd and ≥ 1 and degree ≥ 0.
void validate_smoothing(const SmoothingParams& params, std::string_view where);
// True when the filter returns its input unchanged: window 1 or degree ≥ window − 1.
[[nodiscard]] bool smoothing_is_identity(const SmoothingParams& params);

// Smooths channels that share one time base, in place, with one set of weights per sample
// (SENSOR-SPEC §5). time_s strictly increasing; every channel as long as time_s.
void savitzky_golay_in_place(std::span<const double> time_s,
                             std::span<std::vector<double>* const> channels,
                             const SmoothingParams& params);
// One channel on the given times  (SENSOR-SPEC §5)
[[nodiscard]] std::vector<double> savitzky_golay(std::span<const double> time_s,
                                                 std::span<const double> values,
                                                 const SmoothingParams& params);
// One channel sampled uniformly (time = sample index)  (SENSOR-SPEC §5)
[[nodiscard]] std::vector<double> savitzky_golay(std::span<const double> values,
                                                 const SmoothingParams& params);
// The weights of the classical (uniform, centred) filter: smoothed value = Σ w_k · y_k,
// k = −window/2 … window/2. Σ w_k² is the factor by which white-noise variance drops.
[[nodiscard]] std::vector<double> savitzky_golay_centre_weights(const SmoothingParams& params);

}  // namespace owsim
