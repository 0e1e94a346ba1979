#include "engine/frame_simulator.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>

#include "engine/flush_to_zero.hpp"
#include "geometry/error.hpp"
#include "sensor/scan_params_check.hpp"

namespace owsim {
namespace {

// Lines a task builds, traces and receives in one go (a chunk of ~512 pulses: its rays and
// candidates stay in the core's cache between the three steps).
constexpr int kLinesPerTask = 4;
// Pulses whose first-return range-noise draws are made together, ahead of their receiver pass.
constexpr std::size_t kNoiseDrawsAhead = 256;
// A pulse's entry in receive_range's run when it is not a batch slot.
constexpr std::int16_t kGeneralPath = -1;  // the receiver's general path
constexpr std::int16_t kNoReturn = -2;     // met nothing and no false trigger: no return

}  // namespace

FrameSimulator::FrameSimulator(const FrameSimulatorParams& params, const EmbreeScene& scene,
                               TraceApi api)
    : params_(params),
      ray_builder_(params.scan, params.mount),
      noise_(receiver_noise(params.receiver)),
      tracer_(scene, api, noise_),
      weather_(scene.scene().fog, scene.scene().fog_backscatter_ratio_sr,
               fog_object_index(scene.scene()), params.receiver),
      named_objects_(named_object_count(scene.scene())),
      single_returns_(SingleReturnBatch(params.receiver, noise_.on())) {
  validate(params_.receiver);
}

FrameSimulator::BlockRecords FrameSimulator::BlockScratch::records(std::size_t count) {
  // Grown, never shrunk: a frame's last, shorter block leaves the buffers as they are.
  if (pulses.size() < count) {
    pulses.resize(count);
    rays.resize(count);
    active.resize(count);
    returns.resize(count);
    object_returns.resize(count);
  }
  return BlockRecords{std::span(pulses).first(count), std::span(rays).first(count),
                      std::span(active).first(count), std::span(returns).first(count),
                      std::span(object_returns).first(count)};
}

FrameSimulator::BlockRecords FrameSimulator::frame_records(FrameResult& out, std::size_t begin,
                                                           std::size_t count) {
  return BlockRecords{
      std::span(out.pulses).subspan(begin, count), std::span(out.rays).subspan(begin, count),
      std::span(out.active).subspan(begin, count), std::span(out.returns).subspan(begin, count),
      std::span(out.object_returns).subspan(begin, count)};
}

void FrameSimulator::prepare(std::int64_t frame, const PoseSource& poses, FrameResult& out,
                             FrameRecordScope records) const {
  const ScanParams& scan = params_.scan;
  const auto count =
      records == FrameRecordScope::frame ? static_cast<std::size_t>(scan.pulses_per_frame()) : 0;
  out.frame = frame;
  out.pulses.resize(count);
  out.rays.resize(count);
  out.active.resize(count);
  out.returns.resize(count);
  out.object_returns.resize(count);

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
                      const BlockRecords block = frame_records(
                          out,
                          static_cast<std::size_t>(lines.begin() * params_.scan.fibers_per_line),
                          static_cast<std::size_t>(lines.size() * params_.scan.fibers_per_line));
                      ray_builder_.build_lines(out.sweep, poses, lines.begin(), lines.end(),
                                               block.pulses, block.rays, block.active);
                    });
}

void FrameSimulator::receive_range(std::int64_t frame, const BlockRecords& block,
                                   std::span<const PulseCandidates> candidates, int begin) const {
  const int end = begin + static_cast<int>(block.returns.size());
  const ScanParams& scan = params_.scan;
  const ReceiverParams& receiver = params_.receiver;
  std::array<Candidate, PulseCandidates::kMaxWires + 1> gathered;
  WeatherCandidates weathered;
  PathBusyIntervals busy;
  // Pulse k's returns, by the cheapest path that gives them.
  const auto receive_pulse = [&](int k, std::size_t index, PulseReturns& returns,
                                 const PhiloxBlock* first_range_noise) {
    if (block.active[index] == 0) {
      returns = PulseReturns{};
      returns.counter1 = reference_counter(scan.reference_counts, receiver, params_.seed, frame, k);
      returns.counter2 = receiver.counter.timeout_counts;
      return;
    }
    const PulseCandidates& met = candidates[static_cast<std::size_t>(k - begin)];
    // SENSOR-SPEC §11: with the receiver's noise on every pulse may hold false returns; off, the
    // default PulseNoise is §7's deterministic receiver.
    PulseNoise noise;
    if (noise_.on()) {
      noise.model = &noise_;
      noise.background = met.has_solid() ? met.solid_background() : noise_.sky_background();
    }
    noise.first_range_noise = first_range_noise;
    if (!weather_.empty()) {
      const std::span<Candidate> weathered_met =
          weathered_candidates(weather_, block.rays[index], met, receiver, weathered, &busy);
      noise.busy = busy.span();
      select_returns(weathered_met, receiver, params_.seed, frame, k, returns, noise);
      return;
    }
    // Most pulses meet one surface or none and no wire: no gathering for them.
    if (met.wires().empty()) {
      if (met.has_solid()) {
        select_single_return(met.solid(), receiver, params_.seed, frame, k, returns, noise);
      } else {
        select_returns({}, receiver, params_.seed, frame, k, returns, noise);
      }
      return;
    }
    select_returns(met.gather(gathered), receiver, params_.seed, frame, k, returns, noise);
  };
  // A run of pulses at once: the common pulse — one surface, no wire, clear air, no false trigger
  // in its group — decided by its echo alone over arrays (sensor/single_return_batch.hpp), one
  // that met nothing has no return; the others, and any the batch leaves undecided, take the
  // receiver's general path. The first return's range-noise draws are made on vector lanes for
  // the pulses that may have a return, and for them only (the same bits as one at a time:
  // geometry/keyed_random.hpp random_blocks); a pulse that met nothing in a quiet group, or the
  // reference fiber's (which draws its own), has none.
  const bool range_noise = range_noise_sigma_m(receiver) != 0.0;
  std::array<std::int64_t, kNoiseDrawsAhead> drawn_pulse;  // draw d is pulse drawn_pulse[d]'s
  std::array<PhiloxBlock, kNoiseDrawsAhead> first_range_noise;
  std::array<double, kNoiseDrawsAhead> first_normals;
  std::array<std::int16_t, kNoiseDrawsAhead> draw_of;     // pulse run + at's draw, or −1
  std::array<std::int16_t, kNoiseDrawsAhead> batch_draw;  // batch slot s's draw
  std::array<std::int16_t, kNoiseDrawsAhead> batch_slot;
  static_assert(kNoiseDrawsAhead <= SingleReturnBatch::kCapacity);
  SingleReturnBatch& batch = single_returns_.local();
  for (int run = begin; run < end; run += static_cast<int>(kNoiseDrawsAhead)) {
    const int run_end = std::min(end, run + static_cast<int>(kNoiseDrawsAhead));
    batch.clear();
    std::size_t draws = 0;
    // group_has_no_trigger, its group's draw taken once for the pulses of the group.
    std::int64_t quiet_group = -1;
    bool quiet = false;
    for (int k = run; k < run_end; ++k) {
      const auto at = static_cast<std::size_t>(k - run);
      const PulseCandidates& met = candidates[static_cast<std::size_t>(k - begin)];
      batch_slot[at] = kGeneralPath;
      draw_of[at] = -1;
      if (block.active[static_cast<std::size_t>(k - begin)] == 0) continue;
      bool general = !weather_.empty() || !met.wires().empty();
      if (!general && noise_.on()) {
        const double background =
            met.has_solid() ? met.solid_background() : noise_.sky_background();
        const std::int64_t group = k / ReceiverNoise::kTriggerGroup;
        if (group != quiet_group) {
          quiet_group = group;
          quiet = noise_.group_is_quiet(params_.seed, frame, group);
        }
        general = !quiet || !(background <= noise_.max_background());
      }
      if (!general && !met.has_solid()) {  // nothing met, no false trigger: no return
        batch_slot[at] = kNoReturn;
        continue;
      }
      draw_of[at] = static_cast<std::int16_t>(draws);
      drawn_pulse[draws] = k;
      if (!general) {
        batch_draw[batch.size()] = static_cast<std::int16_t>(draws);
        batch_slot[at] = static_cast<std::int16_t>(
            batch.add(met.solid(), met.solid_background(), 0.0));  // its normal set below
      }
      ++draws;
    }
    if (range_noise) {
      random_blocks(params_.seed, frame, std::span<const std::int64_t>(drawn_pulse.data(), draws),
                    RandomPurpose::range_noise_first, std::span(first_range_noise.data(), draws));
      first_block_normals(std::span(first_range_noise.data(), draws),
                          std::span(first_normals.data(), draws));
      for (std::size_t slot = 0; slot < batch.size(); ++slot) {
        batch.set_range_noise_normal(slot,
                                     first_normals[static_cast<std::size_t>(batch_draw[slot])]);
      }
    }
    batch.evaluate();
    for (int k = run; k < run_end; ++k) {
      const auto index = static_cast<std::size_t>(k - begin);
      const auto at = static_cast<std::size_t>(k - run);
      PulseReturns& returns = block.returns[index];
      const int slot = batch_slot[at];
      if (slot == kNoReturn) {
        set_no_returns(receiver, returns);
      } else if (slot >= 0 && batch.outcome(static_cast<std::size_t>(slot)) !=
                                  SingleReturnBatch::Outcome::undecided) {
        batch.write(static_cast<std::size_t>(slot), candidates[index].solid(), returns);
      } else {
        const int draw = draw_of[at];
        receive_pulse(k, index, returns,
                      range_noise && draw >= 0 ? &first_range_noise[static_cast<std::size_t>(draw)]
                                               : nullptr);
      }
      // While the returns are in registers: no pass over the 88-byte records later.
      block.object_returns[index] = object_return_bits(returns, named_objects_);
    }
  }
}

void FrameSimulator::receive(FrameResult& out, std::span<const PulseCandidates> candidates) const {
  if (candidates.size() != out.returns.size()) {
    throw Error("engine: the candidates do not match the frame's pulses");
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, params_.scan.pulses_per_frame(), 1024),
                    [&](const auto& range) {
                      const FlushDenormalsToZero ftz;
                      const auto first = static_cast<std::size_t>(range.begin());
                      receive_range(out.frame, frame_records(out, first, range.size()),
                                    candidates.subspan(first, range.size()), range.begin());
                    });
}

void FrameSimulator::simulate(std::int64_t frame, const PoseSource& poses, FrameResult& out,
                              const FrameBlockDone& block_done, FrameRecordScope records) const {
  prepare(frame, poses, out, records);
  const int fibers = params_.scan.fibers_per_line;
  // Each task takes its lines through all three steps while their data is in cache; the result
  // is the same as build_rays, trace and receive one after the other (each pulse depends only on
  // its own ray and keys).
  tbb::parallel_for(
      tbb::blocked_range<int>(0, params_.scan.lines_per_frame, kLinesPerTask),
      [&](const auto& lines) {
        const FlushDenormalsToZero ftz;
        std::vector<PulseCandidates>& candidates = block_candidates_.local();
        candidates.resize(static_cast<std::size_t>(kLinesPerTask * fibers));
        BlockScratch& scratch = block_scratch_.local();
        for (int first = lines.begin(); first < lines.end(); first += kLinesPerTask) {
          const int last = std::min(lines.end(), first + kLinesPerTask);
          const auto begin = static_cast<std::size_t>(first * fibers);
          const auto count = static_cast<std::size_t>((last - first) * fibers);
          const BlockRecords block = records == FrameRecordScope::frame
                                         ? frame_records(out, begin, count)
                                         : scratch.records(count);
          ray_builder_.build_lines(out.sweep, poses, first, last, block.pulses, block.rays,
                                   block.active);
          const std::span<PulseCandidates> met(candidates.data(), count);
          // Ray ids are block-relative: the block's rays, flags and candidates start at 0.
          tracer_.trace_range(block.rays, block.active, met, 0, static_cast<unsigned>(count));
          receive_range(frame, block, met, static_cast<int>(begin));
          if (block_done) {
            block_done(out,
                       FrameView{frame, out.sweep, block.pulses, block.rays, block.returns,
                                 block.object_returns},
                       static_cast<int>(begin));
          }
        }
      },
      tbb::simple_partitioner{});
}

}  // namespace owsim
