#pragma once
// One frame of the sensor, simulated whole (DESIGN.md data flow: ScanPattern → FrameRays → Embree
// trace → Receiver → pulse returns). A frame is the unit of work: it depends only on the scenario
// and its index, so frames can be simulated in any order on any thread with the same bytes out.
// Set up once (may allocate, may throw); simulate() reuses the caller's FrameResult buffers, so a
// worker that keeps one FrameResult allocates nothing per frame after the first.
#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "engine/frame_tracer.hpp"
#include "sensor/frame_rays.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/mounting.hpp"
#include "sensor/pose_source.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"
#include "sensor/single_return_batch.hpp"
#include "sensor/weather.hpp"

namespace owsim {

struct FrameResult {
  std::int64_t frame = 0;
  int buffer = 0;  // the slot of the flight pipeline's pool holding it (0..frames in flight − 1)
  FrameSweep sweep;
  std::vector<Pulse> pulses;         // the scan pattern, firing order
  std::vector<PulseRay> rays;        // the central ray of each pulse (local ENU)
  std::vector<std::uint8_t> active;  // 0 for the reference fiber
  // What the receiver recorded. For the reference fiber (inactive) count is 0 and counter1 holds
  // the reference range counter of SENSOR-SPEC §8.
  std::vector<PulseReturns> returns;
  // object_return_bits of each pulse's returns (bit r: returns[r] lies on a named scene object),
  // written with them: what the ground truth tallies, without a second pass over `returns`.
  std::vector<std::uint8_t> object_returns;

  [[nodiscard]] FrameView view() const {
    return FrameView{frame, sweep, pulses, rays, returns, object_returns};
  }
};

struct FrameSimulatorParams {
  ScanParams scan;
  ReceiverParams receiver;
  Mount mount;
  std::uint64_t seed = 0;
};

// Called by the worker that simulated pulses [begin, end) of `frame` right after their receiver
// pass, while that block's pulses and returns are still in its cache: concurrently for disjoint
// blocks of a frame, in any order. Blocks start and end on line boundaries.
using FrameBlockDone = std::function<void(const FrameResult& frame, int begin, int end)>;

class FrameSimulator {
 public:
  FrameSimulator(const FrameSimulatorParams& params, const EmbreeScene& scene, TraceApi api);

  // Pattern, rays, trace and the receiver post-pass for one frame, in parallel over blocks of
  // lines; the same result as build_rays, a trace and receive in turn. A block's candidates live
  // only in its worker's scratch buffer, between its trace and its receiver pass. `block_done`
  // (may be empty) is called for each block when its returns are complete; an exception it
  // throws stops the frame and reaches the caller.
  void simulate(std::int64_t frame, const PoseSource& poses, FrameResult& out,
                const FrameBlockDone& block_done = {}) const;
  // The pattern and rays alone (no trace): what `trace-only` benchmarks and the brute-force
  // reference start from.
  void build_rays(std::int64_t frame, const PoseSource& poses, FrameResult& out) const;
  // The receiver post-pass over a whole frame's candidates, one per pulse of out (after a trace
  // of out.rays by any tracer).
  void receive(FrameResult& out, std::span<const PulseCandidates> candidates) const;

  [[nodiscard]] const FrameSimulatorParams& params() const { return params_; }
  [[nodiscard]] const FrameTracer& tracer() const { return tracer_; }

 private:
  // Sizes out's buffers for the frame and sets its index and sweep.
  void prepare(std::int64_t frame, const PoseSource& poses, FrameResult& out) const;
  // Returns of pulses [begin, end) of out; candidates[k − begin] belongs to pulse k.
  void receive_range(FrameResult& out, std::span<const PulseCandidates> candidates, int begin,
                     int end) const;

  FrameSimulatorParams params_;
  FrameRayBuilder ray_builder_;
  ReceiverNoise noise_;  // SENSOR-SPEC §11; off: the deterministic receiver
  FrameTracer tracer_;
  WeatherMedia weather_;           // the scene's fog volumes (SENSOR-SPEC §10); empty in clear air
  std::size_t named_objects_ = 0;  // the scene's named_object_count
  // Each worker's candidates for the block of lines it is tracing (simulate).
  mutable tbb::enumerable_thread_specific<std::vector<PulseCandidates>> block_candidates_;
  // Each worker's batch of single-return pulses (receive_range).
  mutable tbb::enumerable_thread_specific<SingleReturnBatch> single_returns_;
};

}  // namespace owsim
