#pragma once
// A read-only view of one simulated frame — what the output sinks (io/) consume, without
// depending on the engine that produced it.
#include <cstddef>
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

// Pulses [begin, end) of a whole frame's view as a view of their own — a block's records, as
// FrameBlockDone (engine/frame_simulator.hpp) and FrameEncoder::encode_pulses take them: entry 0
// is pulse `begin`. Requires begin ≤ end ≤ frame.pulses.size().
[[nodiscard]] inline FrameView frame_block(const FrameView& frame, std::size_t begin,
                                           std::size_t end) {
  const std::size_t count = end - begin;
  return FrameView{frame.frame,
                   frame.sweep,
                   frame.pulses.subspan(begin, count),
                   frame.rays.subspan(begin, count),
                   frame.returns.subspan(begin, count),
                   frame.object_returns.empty() ? frame.object_returns
                                                : frame.object_returns.subspan(begin, count)};
}

}  // namespace owsim
