#pragma once
// A flight as a stream of frames (DESIGN.md "Flight pipeline"): tbb::parallel_pipeline with a
// serial in-order source (frame indices), parallel frame simulation (with an optional step on
// each block of pulses as it completes and an optional `prepare` step on the whole frame after
// it, e.g. encoding the frame's outputs), and a serial in-order sink.
// At most `frames_in_flight` frames exist at once, each in a FrameResult recycled from a fixed
// pool (FrameResult::buffer names its slot), so memory stays flat however long the flight. The
// sink sees frames in index order.
#include <cstdint>
#include <functional>

#include "engine/frame_simulator.hpp"
#include "sensor/pose_source.hpp"

namespace owsim {

struct FlightRange {
  std::int64_t first_frame = 0;
  std::int64_t frame_count = 0;
};

// Called once per frame, in frame order, never concurrently. May throw: the pipeline stops and
// the exception reaches the caller of run_flight.
using FrameSink = std::function<void(const FrameResult&)>;
// Called once per frame right after its simulation, on any thread, concurrently for different
// frames (never for two frames in the same buffer). May throw, as the sink.
using FramePrepare = std::function<void(const FrameResult&)>;

void run_flight(const FrameSimulator& simulator, const PoseSource& poses, const FlightRange& range,
                int frames_in_flight, const FrameSink& sink);
// The same with `prepare` (may be empty) run on each frame in the parallel stage.
void run_flight(const FrameSimulator& simulator, const PoseSource& poses, const FlightRange& range,
                int frames_in_flight, const FramePrepare& prepare, const FrameSink& sink);
// The same with `block_done` (may be empty) run on each block of a frame as its simulation
// completes it (FrameSimulator::simulate), before `prepare` runs on the whole frame; with
// FrameRecordScope::block the frames given to `prepare` and `sink` hold no per-pulse records
// (block_done alone sees them).
void run_flight(const FrameSimulator& simulator, const PoseSource& poses, const FlightRange& range,
                int frames_in_flight, const FrameBlockDone& block_done, const FramePrepare& prepare,
                const FrameSink& sink, FrameRecordScope records = FrameRecordScope::frame);

}  // namespace owsim
