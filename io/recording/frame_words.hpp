#pragma once
// One simulated frame packed into the sensor's native words (SENSOR-SPEC §8): what the real
// MilOWS or HELLAS would have written for those pulses. Pure packing: the pulse table comes from
// sensor/scan_pattern.hpp and the counters from the receiver; nothing is recomputed here.
#include <cstdint>
#include <span>

#include "sensor/receiver.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

// Fills out[k] with the 64-bit MilOWS word of pulse k: time tag, encoder, FG/LG, counter 1 and 2
// (the timeout where there is no return; the reference fiber carries its reference counter).
void pack_milows_frame(std::span<const Pulse> pulses, std::span<const PulseReturns> returns,
                       std::span<std::uint64_t> out);

// Fills out[k] with the 32-bit HELLAS word of pulse k: ZT/BT active low, time tag, Ain, NI,
// MovDir, counter 1.
void pack_hellas_frame(const ScanParams& scan, const FrameSweep& sweep,
                       std::span<const Pulse> pulses, std::span<const PulseReturns> returns,
                       std::span<std::uint32_t> out);

// The header word that starts a HELLAS file: Select = 1, bits 0–11 the mirror angle before the
// first pulse, round((β_start + 20.48°)/0.01°)  (SENSOR-SPEC §8 pinned HELLAS details)
[[nodiscard]] std::uint32_t hellas_file_header_word(const FrameSweep& first_sweep, double time_s);

}  // namespace owsim
