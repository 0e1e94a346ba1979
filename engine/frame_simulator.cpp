#include "engine/frame_simulator.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/scan_params_check.hpp"

namespace owsim {

FrameSimulator::FrameSimulator(const FrameSimulatorParams& params, const EmbreeScene& scene,
                               TraceApi api)
    : params_(params), tracer_(scene, api) {
  validate(params_.scan);
  validate(params_.receiver);
}

void FrameSimulator::build_rays(std::int64_t frame, const PoseSource& poses,
                                FrameResult& out) const {
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

  // Each pulse is placed with the pose at its own firing time (16 µs apart).
  tbb::parallel_for(tbb::blocked_range<int>(0, scan.lines_per_frame), [&](const auto& lines) {
    for (int line = lines.begin(); line < lines.end(); ++line) {
      for (int slot = 0; slot < scan.fibers_per_line; ++slot) {
        const int k = line * scan.fibers_per_line + slot;
        const auto index = static_cast<std::size_t>(k);
        const Pulse pulse = pulse_of_frame(scan, out.sweep, k);
        out.pulses[index] = pulse;
        if (pulse.reference) {
          out.active[index] = 0;
          out.rays[index] = PulseRay{};
          continue;
        }
        const SensorPlacement placement =
            sensor_placement(poses.pose_at(pulse.time_s), params_.mount, scan.model);
        out.active[index] = 1;
        out.rays[index] = PulseRay{placement.origin_enu_m,
                                   ray_direction_enu(placement, pulse.alpha_deg, pulse.beta_deg)};
      }
    }
  });
}

void FrameSimulator::receive(FrameResult& out) const {
  const ScanParams& scan = params_.scan;
  const ReceiverParams& receiver = params_.receiver;
  const int count = scan.pulses_per_frame();
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 1024), [&](const auto& range) {
    std::array<Candidate, PulseCandidates::kMaxWires + 1> gathered;
    for (int k = range.begin(); k < range.end(); ++k) {
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
  });
}

void FrameSimulator::simulate(std::int64_t frame, const PoseSource& poses, FrameResult& out) const {
  build_rays(frame, poses, out);
  tracer_.trace(out.rays, out.active, out.candidates);
  receive(out);
}

}  // namespace owsim
