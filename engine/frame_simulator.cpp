#include "engine/frame_simulator.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/flush_to_zero.hpp"
#include "geometry/error.hpp"
#include "sensor/scan_params_check.hpp"

namespace owsim {
namespace {

// Lines a task builds, traces and receives in one go (a chunk of ~512 pulses: its rays and
// candidates stay in the core's cache between the three steps).
constexpr int kLinesPerTask = 4;

}  // namespace

FrameSimulator::FrameSimulator(const FrameSimulatorParams& params, const EmbreeScene& scene,
                               TraceApi api)
    : params_(params), ray_builder_(params.scan, params.mount), tracer_(scene, api) {
  validate(params_.receiver);
}

void FrameSimulator::prepare(std::int64_t frame, const PoseSource& poses, FrameResult& out) const {
  const ScanParams& scan = params_.scan;
  const auto count = static_cast<std::size_t>(scan.pulses_per_frame());
  out.frame = frame;
  out.pulses.resize(count);
  out.rays.resize(count);
  out.active.resize(count);
  out.candidates.resize(count);
  out.returns.resize(count);

  const double frame_start = pulse_time_s(scan, frame, 0);
  const double shift = look_into_turn_shift_deg(scan, poses.heading_rate_deg_per_s(frame_start));
  out.sweep = frame_sweep(scan, params_.seed, frame, shift);
}

void FrameSimulator::build_rays(std::int64_t frame, const PoseSource& poses,
                                FrameResult& out) const {
  prepare(frame, poses, out);
  tbb::parallel_for(tbb::blocked_range<int>(0, params_.scan.lines_per_frame, kLinesPerTask),
                    [&](const auto& lines) {
                      const FlushDenormalsToZero ftz;
                      ray_builder_.build_lines(out.sweep, poses, lines.begin(), lines.end(),
                                               out.pulses, out.rays, out.active);
                    });
}

void FrameSimulator::receive_range(FrameResult& out, int begin, int end) const {
  const ScanParams& scan = params_.scan;
  const ReceiverParams& receiver = params_.receiver;
  std::array<Candidate, PulseCandidates::kMaxWires + 1> gathered;
  for (int k = begin; k < end; ++k) {
    const auto index = static_cast<std::size_t>(k);
    PulseReturns& returns = out.returns[index];
    if (out.active[index] == 0) {
      returns = PulseReturns{};
      returns.counter1 =
          reference_counter(scan.reference_counts, receiver, params_.seed, out.frame, k);
      returns.counter2 = receiver.counter.timeout_counts;
      continue;
    }
    returns = select_returns(out.candidates[index].gather(gathered), receiver, params_.seed,
                             out.frame, k);
  }
}

void FrameSimulator::receive(FrameResult& out) const {
  tbb::parallel_for(tbb::blocked_range<int>(0, params_.scan.pulses_per_frame(), 1024),
                    [&](const auto& range) {
                      const FlushDenormalsToZero ftz;
                      receive_range(out, range.begin(), range.end());
                    });
}

void FrameSimulator::simulate(std::int64_t frame, const PoseSource& poses, FrameResult& out) const {
  prepare(frame, poses, out);
  const int fibers = params_.scan.fibers_per_line;
  // Each task takes its lines through all three steps while their data is in cache; the result
  // is the same as build_rays, trace and receive one after the other (each pulse depends only on
  // its own ray and keys).
  tbb::parallel_for(
      tbb::blocked_range<int>(0, params_.scan.lines_per_frame, kLinesPerTask),
      [&](const auto& lines) {
        const FlushDenormalsToZero ftz;
        for (int first = lines.begin(); first < lines.end(); first += kLinesPerTask) {
          const int last = std::min(lines.end(), first + kLinesPerTask);
          ray_builder_.build_lines(out.sweep, poses, first, last, out.pulses, out.rays, out.active);
          const auto begin = static_cast<unsigned>(first * fibers);
          const auto end = static_cast<unsigned>(last * fibers);
          tracer_.trace_range(out.rays, out.active, out.candidates, begin, end);
          receive_range(out, static_cast<int>(begin), static_cast<int>(end));
        }
      },
      tbb::simple_partitioner{});
}

}  // namespace owsim
