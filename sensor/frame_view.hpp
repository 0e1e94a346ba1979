#pragma once
// A read-only view of one simulated frame — what the output sinks (io/) consume, without
// depending on the engine that produced it.
#include <cstdint>
#include <span>

#include "sensor/pulse_candidates.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

struct FrameView {
  std::int64_t frame = 0;
  FrameSweep sweep;
  std::span<const Pulse> pulses;          // firing order
  std::span<const PulseRay> rays;         // central ray of each pulse (local ENU)
  std::span<const PulseReturns> returns;  // reference fiber: count 0, counter1 = reference
  // object_return_bits of each pulse's returns, as the engine's receiver pass records them; empty
  // when the frame's producer did not (a reader then derives them from `returns`).
  std::span<const std::uint8_t> object_returns = {};
};

}  // namespace owsim
