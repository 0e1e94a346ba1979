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

// Where simulate() keeps a frame's per-pulse records (pulses, rays, active flags, returns, object
// bits). `frame`: in the FrameResult, whole, for whoever reads the frame afterwards. `block`: only
// in the worker's scratch for the block being simulated, handed to FrameBlockDone and then
// overwritten; the FrameResult's record vectors are left empty. A reader that needs only each
// block once (the words, the tally) takes `block`: the frame's 4 MB of records (corridor) then
// never leave the cores' caches.
enum class FrameRecordScope { frame, block };

// Called by the worker that simulated pulses [begin, begin + block.pulses.size()) of `frame` right
// after their receiver pass, while that block's records are still in its cache: concurrently for
// disjoint blocks of a frame, in any order. Blocks start and end on line boundaries. `block` holds
// those pulses' records only (its first entry is pulse `begin`); `frame` holds the frame's index
// and sweep, and its records only with FrameRecordScope::frame.
using FrameBlockDone =
    std::function<void(const FrameResult& frame, const FrameView& block, int begin)>;

class FrameSimulator {
 public:
  FrameSimulator(const FrameSimulatorParams& params, const EmbreeScene& scene, TraceApi api);

  // Pattern, rays, trace and the receiver post-pass for one frame, in parallel over blocks of
  // lines; the same result as build_rays, a trace and receive in turn. A block's candidates live
  // only in its worker's scratch buffer, between its trace and its receiver pass. `block_done`
  // (may be empty) is called for each block when its returns are complete; an exception it
  // throws stops the frame and reaches the caller.
  void simulate(std::int64_t frame, const PoseSource& poses, FrameResult& out,
                const FrameBlockDone& block_done = {},
                FrameRecordScope records = FrameRecordScope::frame) const;
  // The pattern and rays alone (no trace): what `trace-only` benchmarks and the brute-force
  // reference start from.
  void build_rays(std::int64_t frame, const PoseSource& poses, FrameResult& out) const;
  // The receiver post-pass over a whole frame's candidates, one per pulse of out (after a trace
  // of out.rays by any tracer).
  void receive(FrameResult& out, std::span<const PulseCandidates> candidates) const;

  [[nodiscard]] const FrameSimulatorParams& params() const { return params_; }
  [[nodiscard]] const FrameTracer& tracer() const { return tracer_; }

 private:
  // One block's records: pulses [begin, begin + size) of a frame, entry 0 pulse `begin`.
  struct BlockRecords {
    std::span<Pulse> pulses;
    std::span<PulseRay> rays;
    std::span<std::uint8_t> active;
    std::span<PulseReturns> returns;
    std::span<std::uint8_t> object_returns;
  };
  // A worker's scratch for one block's records (FrameRecordScope::block).
  struct BlockScratch {
    std::vector<Pulse> pulses;
    std::vector<PulseRay> rays;
    std::vector<std::uint8_t> active;
    std::vector<PulseReturns> returns;
    std::vector<std::uint8_t> object_returns;
    [[nodiscard]] BlockRecords records(std::size_t count);
  };
  [[nodiscard]] static BlockRecords frame_records(FrameResult& out, std::size_t begin,
                                                  std::size_t count);

  // Sizes out's buffers for the frame (empties them for `block`) and sets its index and sweep.
  void prepare(std::int64_t frame, const PoseSource& poses, FrameResult& out,
               FrameRecordScope records = FrameRecordScope::frame) const;
  // Returns of pulses [begin, begin + block size) of `frame`, into the block's records (entry 0
  // pulse `begin`); candidates[k − begin] belongs to pulse k.
  void receive_range(std::int64_t frame, const BlockRecords& block,
                     std::span<const PulseCandidates> candidates, int begin) const;

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
  // Each worker's records for its block (FrameRecordScope::block).
  mutable tbb::enumerable_thread_specific<BlockScratch> block_scratch_;
};

}  // namespace owsim
