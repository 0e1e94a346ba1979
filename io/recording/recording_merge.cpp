#include "io/recording/recording_merge.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <system_error>
#include <vector>

#include "engine/frame_tracer.hpp"
#include "geometry/error.hpp"
#include "io/recording/hellas_word.hpp"
#include "io/recording/milows_word.hpp"
#include "io/recording/word_file.hpp"
#include "sensor/hellas_scan.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/scan_pattern.hpp"
#include "sensor/weather.hpp"

namespace owsim {
namespace {

enum class Source : std::uint8_t { synthetic, recorded_first, recorded_second };

struct Entry {
  std::uint16_t counter = 0;
  Source source = Source::synthetic;
};

bool same_source(Source a, Source b) {
  return (a == Source::synthetic) == (b == Source::synthetic);
}

bool same_path(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error_a, error_b;
  const auto canonical_a = std::filesystem::weakly_canonical(a, error_a);
  const auto canonical_b = std::filesystem::weakly_canonical(b, error_b);
  return !error_a && !error_b && canonical_a == canonical_b;
}

// Does the simulator's sweep of this frame reproduce what the recording holds?
bool sweep_reproduces(const ScanParams& scan, const FrameSweep& sweep, const DecodedFrame& frame,
                      const RecordingLayout& layout) {
  if (scan.model == SensorModel::milows) {
    return std::all_of(frame.pulses.begin(), frame.pulses.end(), [&](const Pulse& pulse) {
      return pulse_of_frame(scan, sweep, pulse.index).encoder == pulse.encoder;
    });
  }
  if (sweep.direction != frame.sweep.direction) return false;
  const int expected_ni = hellas_ni_pulse(scan, sweep);
  const int first = frame.pulses.front().index;
  const int last = frame.pulses.back().index;
  if (frame.ni_pulse >= 0 ? frame.ni_pulse != expected_ni
                          : expected_ni >= first && expected_ni <= last) {
    return false;
  }
  if (frame.first_word == layout.first_pulse_word && first == 0 && layout.hellas_header_code) {
    return *layout.hellas_header_code == hellas_header_beta_code(sweep.mirror_beta_start_deg);
  }
  return true;
}

std::uint64_t rewrite_word(SensorModel model, std::uint64_t bits, const MergedCounters& merged) {
  if (model == SensorModel::milows) {
    MilowsWord word = unpack_milows(bits);
    word.counter1 = merged.counter1;
    word.counter2 = merged.counter2;
    return pack(word);
  }
  HellasWord word = unpack_hellas(static_cast<std::uint32_t>(bits));
  word.counter = merged.counter1;
  return pack(word);
}

}  // namespace

MergedCounters merge_pulse_counters(std::uint16_t recorded1, std::uint16_t recorded2,
                                    bool second_field, const PulseReturns& synthetic,
                                    std::optional<std::uint16_t> synthetic_solid_counter,
                                    const ReceiverParams& receiver) {
  const std::uint16_t timeout = receiver.counter.timeout_counts;
  MergedCounters out;
  out.counter1 = recorded1;
  out.counter2 = recorded2;

  // The recorded returns the synthetic solid leaves visible.
  std::array<Entry, 2> recorded{};
  int recorded_count = 0;
  const std::array<Entry, 2> stored = {
      Entry{recorded1, Source::recorded_first},
      Entry{second_field ? recorded2 : timeout, Source::recorded_second}};
  for (const Entry& entry : stored) {
    if (entry.counter >= timeout) continue;
    if (synthetic_solid_counter && *synthetic_solid_counter < entry.counter) {
      ++out.recorded_hidden;
      continue;
    }
    recorded[static_cast<std::size_t>(recorded_count++)] = entry;
  }
  const bool nearer =
      synthetic.count > 0 && (recorded_count == 0 || synthetic.counter1 < recorded[0].counter);
  if (!nearer && out.recorded_hidden == 0) return out;

  // Synthetic returns first, so a tie in counts goes to the synthetic one (stable sort).
  std::array<Entry, 4> pool{};
  std::size_t pooled = 0;
  for (int r = 0; r < synthetic.count; ++r) {
    pool[pooled++] = Entry{synthetic.returns[r].counter, Source::synthetic};
  }
  for (int r = 0; r < recorded_count; ++r) pool[pooled++] = recorded[static_cast<std::size_t>(r)];
  std::stable_sort(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(pooled),
                   [](const Entry& a, const Entry& b) { return a.counter < b.counter; });

  const double count_m = range_per_count_m(receiver.counter);
  const Entry* chosen[2] = {nullptr, nullptr};
  if (pooled > 0) chosen[0] = &pool[0];
  for (std::size_t i = 1; second_field && i < pooled; ++i) {
    const bool separated =
        (pool[i].counter - pool[0].counter) * count_m >= receiver.min_return_separation_m;
    if (same_source(pool[i].source, pool[0].source) || separated) {
      chosen[1] = &pool[i];
      break;
    }
  }
  out.counter1 = chosen[0] != nullptr ? chosen[0]->counter : timeout;
  if (second_field) out.counter2 = chosen[1] != nullptr ? chosen[1]->counter : timeout;

  int recorded_kept = 0;
  for (const Entry* entry : chosen) {
    if (entry == nullptr) continue;
    if (entry->source == Source::synthetic) {
      ++out.synthetic_written;
    } else {
      ++recorded_kept;
    }
  }
  out.recorded_moved = chosen[1] != nullptr && chosen[1]->source == Source::recorded_first ? 1 : 0;
  out.recorded_dropped = recorded_count - recorded_kept;
  out.changed = out.counter1 != recorded1 || (second_field && out.counter2 != recorded2);
  if (!out.changed) return MergedCounters{recorded1, recorded2};  // as recorded: nothing to count
  return out;
}

MergeReport merge_recording(RecordingDecoder& decoder, const RecordingScene& scene,
                            const Scenario& scenario, const MergeOptions& options) {
  if (same_path(options.out, decoder.path())) {
    throw input_error(options.out.string(),
                      "is the recording being merged into; write the merged file elsewhere");
  }
  const ScanParams& scan = decoder.scan();
  const RecordingLayout& layout = decoder.layout();
  const ReceiverParams& receiver = scenario.receiver;
  const bool milows = scan.model == SensorModel::milows;

  if (options.out.has_parent_path()) {
    std::error_code error;
    std::filesystem::create_directories(options.out.parent_path(), error);
    if (error) {
      throw file_error(options.out.parent_path().string(),
                       "cannot create the output folder: " + error.message());
    }
  }
  std::optional<MilowsWordWriter> milows_out;
  std::optional<HellasWordWriter> hellas_out;
  if (milows) {
    milows_out.emplace(options.out);
  } else {
    hellas_out.emplace(options.out);
    if (layout.hellas_header_word) hellas_out->write(*layout.hellas_header_word);
  }

  const FrameTracer tracer(scene.embree_scene(), TraceApi::stream);
  const Scene& objects = scene.scene();
  const WeatherMedia weather(objects.fog, objects.fog_backscatter_ratio_sr,
                             fog_object_index(objects), receiver);
  MergeReport report;
  DecodedFrame frame;
  std::vector<PulseRay> rays;
  std::vector<std::uint8_t> active;
  std::vector<PulseCandidates> candidates;
  std::vector<MergedCounters> merged;
  std::vector<std::uint32_t> hellas_words;
  while (decoder.next(frame)) {
    ++report.frames;
    report.pulses += frame.size();

    bool rebuilt = false;
    if (layout.timing == RecordingTiming::scenario_grid) {
      const double frame_start = pulse_time_s(scan, frame.frame, 0);
      const double shift =
          look_into_turn_shift_deg(scan, scene.trajectory().heading_rate_deg_per_s(frame_start));
      const FrameSweep sweep = frame_sweep(scan, scenario.seed, frame.frame, shift);
      if (sweep_reproduces(scan, sweep, frame, layout)) {
        for (Pulse& pulse : frame.pulses) pulse = pulse_of_frame(scan, sweep, pulse.index);
        frame.sweep = sweep;
        rebuilt = true;
      }
    }
    ++(rebuilt ? report.frames_sweep_rebuilt : report.frames_sweep_measured);

    pulse_rays(frame.pulses, scene.trajectory(), scenario.mount, scan.model, rays, active);
    candidates.resize(frame.size());
    tracer.trace(rays, active, candidates);
    merged.resize(frame.size());
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, frame.size(), 1024), [&](const auto& range) {
          std::array<Candidate, PulseCandidates::kMaxWires + 1> gathered;
          WeatherCandidates weathered;
          for (std::size_t j = range.begin(); j < range.end(); ++j) {
            const Pulse& pulse = frame.pulses[j];
            if (pulse.reference) {
              merged[j] = MergedCounters{frame.counter1[j], frame.counter2[j]};
              continue;
            }
            // In weather the synthetic echoes cross the scenario's fog (SENSOR-SPEC §10).
            const std::span<Candidate> met =
                weather.empty()
                    ? candidates[j].gather(gathered)
                    : weathered_candidates(weather, rays[j], candidates[j], receiver, weathered);
            const PulseReturns synthetic =
                select_returns(met, receiver, scenario.seed, frame.frame, pulse.index);
            std::optional<std::uint16_t> solid;
            if (candidates[j].has_solid()) {
              solid = counter_from_range(candidates[j].solid().range_m, receiver.counter);
            }
            merged[j] = merge_pulse_counters(frame.counter1[j], frame.counter2[j], milows,
                                             synthetic, solid, receiver);
            if (merged[j].changed)
              frame.words[j] = rewrite_word(scan.model, frame.words[j], merged[j]);
          }
        });
    for (const MergedCounters& pulse : merged) {
      report.words_changed += pulse.changed ? 1 : 0;
      report.synthetic_returns += static_cast<std::uint64_t>(pulse.synthetic_written);
      report.recorded_moved += static_cast<std::uint64_t>(pulse.recorded_moved);
      report.recorded_hidden += static_cast<std::uint64_t>(pulse.recorded_hidden);
      report.recorded_dropped += static_cast<std::uint64_t>(pulse.recorded_dropped);
    }

    if (milows) {
      milows_out->write(std::span<const std::uint64_t>(frame.words));
    } else {
      hellas_words.resize(frame.words.size());
      std::transform(frame.words.begin(), frame.words.end(), hellas_words.begin(),
                     [](std::uint64_t bits) { return static_cast<std::uint32_t>(bits); });
      hellas_out->write(std::span<const std::uint32_t>(hellas_words));
    }
    if (options.on_frame) options.on_frame(report.frames, report.pulses);
  }
  if (milows) {
    milows_out->commit();
  } else {
    hellas_out->commit();
  }
  report.time_tag_mismatches = decoder.time_tag_mismatches();
  return report;
}

}  // namespace owsim
