#include "engine/flight_pipeline.hpp"

#include <tbb/concurrent_queue.h>
#include <tbb/parallel_pipeline.h>

#include <memory>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {

void run_flight(const FrameSimulator& simulator, const PoseSource& poses, const FlightRange& range,
                int frames_in_flight, const FrameSink& sink) {
  run_flight(simulator, poses, range, frames_in_flight, FramePrepare(), sink);
}

void run_flight(const FrameSimulator& simulator, const PoseSource& poses, const FlightRange& range,
                int frames_in_flight, const FramePrepare& prepare, const FrameSink& sink) {
  run_flight(simulator, poses, range, frames_in_flight, FrameBlockDone(), prepare, sink);
}

void run_flight(const FrameSimulator& simulator, const PoseSource& poses, const FlightRange& range,
                int frames_in_flight, const FrameBlockDone& block_done, const FramePrepare& prepare,
                const FrameSink& sink, FrameRecordScope records) {
  if (frames_in_flight < 1) throw Error("engine: frames in flight must be at least 1");
  if (range.frame_count <= 0) return;

  // The buffer pool: one FrameResult per token, reused frame after frame.
  std::vector<std::unique_ptr<FrameResult>> pool;
  tbb::concurrent_queue<FrameResult*> free_buffers;
  for (int i = 0; i < frames_in_flight; ++i) {
    pool.push_back(std::make_unique<FrameResult>());
    pool.back()->buffer = i;
    free_buffers.push(pool.back().get());
  }

  std::int64_t next = range.first_frame;
  const std::int64_t end = range.first_frame + range.frame_count;
  tbb::parallel_pipeline(
      static_cast<std::size_t>(frames_in_flight),
      tbb::make_filter<void, FrameResult*>(tbb::filter_mode::serial_in_order,
                                           [&](tbb::flow_control& control) -> FrameResult* {
                                             if (next >= end) {
                                               control.stop();
                                               return nullptr;
                                             }
                                             FrameResult* buffer = nullptr;
                                             // The pipeline holds at most frames_in_flight tokens,
                                             // so a buffer is always free.
                                             if (!free_buffers.try_pop(buffer))
                                               throw Error("engine: frame buffer pool exhausted");
                                             buffer->frame = next++;
                                             return buffer;
                                           }) &
          tbb::make_filter<FrameResult*, FrameResult*>(
              tbb::filter_mode::parallel,
              [&](FrameResult* buffer) {
                simulator.simulate(buffer->frame, poses, *buffer, block_done, records);
                if (prepare) prepare(*buffer);
                return buffer;
              }) &
          tbb::make_filter<FrameResult*, void>(tbb::filter_mode::serial_in_order,
                                               [&](FrameResult* buffer) {
                                                 sink(*buffer);
                                                 free_buffers.push(buffer);
                                               }));
}

}  // namespace owsim
