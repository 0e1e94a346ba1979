#include "io/recording/recording_decoder_points.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <system_error>
#include <vector>

#include "engine/frame_tracer.hpp"
#include "geometry/error.hpp"
#include "geometry/utm.hpp"
#include "io/points/frame_points.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/ply_writer.hpp"
#include "io/points/points_csv_writer.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/weather.hpp"

namespace owsim {
namespace {

// What the scene says about one recorded return, or nothing.
struct Label {
  bool known = false;
  Candidate candidate;
};

}  // namespace

PulseReturns recorded_returns(std::uint16_t counter1, std::uint16_t counter2,
                              const RangeCounterParams& counter) {
  PulseReturns out;
  out.counter1 = counter1;
  out.counter2 = counter2;
  for (const std::uint16_t count : {counter1, counter2}) {
    if (count >= counter.timeout_counts) continue;
    Return& ret = out.returns[out.count++];
    ret.counter = count;
    ret.range_m = range_from_counter(count, counter);
    ret.true_range_m = ret.range_m;
    ret.energy_rel = std::numeric_limits<double>::quiet_NaN();
    ret.incidence_deg = std::numeric_limits<double>::quiet_NaN();
    ret.object_index = kNoObject;
  }
  return out;
}

std::optional<Candidate> nearest_candidate(std::span<const Candidate> candidates, double range_m,
                                           double tolerance_m) {
  const Candidate* best = nullptr;
  for (const Candidate& candidate : candidates) {
    if (best == nullptr ||
        std::abs(candidate.range_m - range_m) < std::abs(best->range_m - range_m)) {
      best = &candidate;
    }
  }
  if (best == nullptr || !(std::abs(best->range_m - range_m) <= tolerance_m)) return std::nullopt;
  return *best;
}

double label_tolerance_m(const ReceiverParams& receiver) {
  return range_per_count_m(receiver.counter) + 3.0 * range_noise_sigma_m(receiver);
}

DecodeReport decode_recording_points(RecordingDecoder& decoder, const RecordingScene& scene,
                                     const Scenario& scenario, const DecodePointsOptions& options) {
  std::error_code error;
  std::filesystem::create_directories(options.directory, error);
  if (error) {
    throw file_error(options.directory.string(),
                     "cannot create the output folder: " + error.message());
  }
  std::vector<std::unique_ptr<PointSink>> sinks;
  if (options.csv) {
    sinks.push_back(
        std::make_unique<PointsCsvWriter>(options.directory / "points.csv", scene.object_ids()));
  }
  if (options.las) {
    LasWriterOptions las;
    las.origin = scene.local_frame().origin();
    sinks.push_back(std::make_unique<LasWriter>(options.directory / "points.las", las));
  }
  if (options.ply) sinks.push_back(std::make_unique<PlyWriter>(options.directory / "points.ply"));

  const ScanParams& scan = decoder.scan();
  const RangeCounterParams& counter = scenario.receiver.counter;
  const Scene& objects = scene.scene();
  const bool label =
      options.label_from_scene &&
      (!objects.conductors.empty() || !objects.cylinders.empty() || !objects.meshes.empty() ||
       !objects.fog.empty() || scene.embree_scene().has_terrain());
  // Fog returns are labelled with the volume echo SENSOR-SPEC §10 puts on the pulse's path.
  const WeatherMedia weather(objects.fog, objects.fog_backscatter_ratio_sr,
                             fog_object_index(objects), scenario.receiver);
  const double tolerance = label_tolerance_m(scenario.receiver);
  const FrameTracer tracer(scene.embree_scene(), TraceApi::stream);
  const GeodesyCells geodesy(
      scene.local_frame(),
      options.las ? std::optional(utm_grid_of(scene.local_frame().origin())) : std::nullopt);

  DecodeReport report;
  DecodedFrame frame;
  std::vector<PulseRay> rays;
  std::vector<std::uint8_t> active;
  std::vector<PulseCandidates> candidates;
  std::vector<PulseReturns> returns;
  std::vector<Label> labels;  // two per pulse
  std::vector<PointRecord> points;
  std::array<Candidate, PulseCandidates::kMaxWires + 1> gathered;
  WeatherCandidates weathered;
  while (decoder.next(frame)) {
    ++report.frames;
    ++report.frames_by_beta_source[static_cast<std::size_t>(frame.beta_source)];
    report.pulses += frame.size();
    pulse_rays(frame.pulses, scene.trajectory(), scenario.mount, scan.model, rays, active);
    returns.resize(frame.size());
    for (std::size_t j = 0; j < frame.size(); ++j) {
      returns[j] = frame.pulses[j].reference
                       ? PulseReturns{}
                       : recorded_returns(frame.counter1[j], frame.counter2[j], counter);
    }

    labels.assign(2 * frame.size(), Label{});
    if (label) {
      candidates.resize(frame.size());
      tracer.trace(rays, active, candidates);
      for (std::size_t j = 0; j < frame.size(); ++j) {
        const std::span<const Candidate> met =
            weather.empty() ? candidates[j].gather(gathered)
                            : weathered_candidates(weather, rays[j], candidates[j],
                                                   scenario.receiver, weathered);
        for (int r = 0; r < returns[j].count; ++r) {
          if (const auto match = nearest_candidate(met, returns[j].returns[r].range_m, tolerance)) {
            labels[2 * j + static_cast<std::size_t>(r)] = Label{true, *match};
          }
        }
      }
    }

    const FrameView view{frame.frame, frame.sweep, frame.pulses, rays, returns};
    frame_points(view, geodesy, points);
    // frame_points emits the returns pulse by pulse, in return order: walk them the same way.
    std::size_t point = 0;
    for (std::size_t j = 0; j < frame.size(); ++j) {
      for (int r = 0; r < returns[j].count; ++r, ++point) {
        PointRecord& record = points[point];
        const Label& match = labels[2 * j + static_cast<std::size_t>(r)];
        if (r == 1) ++report.second_returns;
        if (!match.known) {
          record.surface.reset();
          record.object_index = kNoObject;
          record.energy_rel = std::numeric_limits<double>::quiet_NaN();
          record.incidence_deg = std::numeric_limits<double>::quiet_NaN();
          continue;
        }
        ++report.labelled_points;
        record.surface = static_cast<SurfaceClass>(match.candidate.surface);
        record.object_index = match.candidate.object_index;
        record.energy_rel = match.candidate.energy_rel;
        record.incidence_deg = match.candidate.incidence_deg;
      }
    }
    report.points += points.size();
    for (auto& sink : sinks) sink->write(points);
    if (options.on_frame) options.on_frame(report.frames, report.pulses);
  }
  for (auto& sink : sinks) sink->finish();
  report.time_tag_mismatches = decoder.time_tag_mismatches();
  return report;
}

}  // namespace owsim
