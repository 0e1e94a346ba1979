#pragma once
// Validation of a ScanParams before it drives a scan (SENSOR-SPEC §1–3, §8): every field a
// scenario can override is checked once, at load, so the per-pulse functions need not.
// A bad field throws owsim::Error naming its scenario key ("sensor.prf_hz: must be …").
#include "sensor/scan_params.hpp"

namespace owsim {

// Throws owsim::Error (input_error with the key "sensor.<field>") for: a non-finite or
// non-positive prf_hz or sweep_deg; fibers_per_line < 2; lines_per_frame < 1; a frame of more
// than 2^31−1 pulses; a sweep that with its jitter leaves ±30°; a negative or non-finite
// sawtooth, jitter, look-into-turn time or limit, or MAF; an α table of the wrong size or with
// |α| > 90° or non-finite; a non-finite start time; a reference count or timeout beyond 12 bits;
// non-positive or non-finite range-counter constants (SENSOR-SPEC §1).
void validate(const ScanParams& p);

}  // namespace owsim
