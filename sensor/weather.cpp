#include "sensor/weather.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/error.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

constexpr double kKoschmieder = 3.912;  // ln 50: 2 % contrast

// How far past a medium's exit a solid still lies on its boundary. The exit (a slab test) and the
// solid's range (its own intersection, e.g. the ground's triangle) are the same point computed two
// ways when the medium stands on the solid: they differ by rounding, ~1e-13 m either way
// (fog_bank: the ground 3e-14 to 1.1e-13 m past the box's floor). A micrometre is far above that
// and far below anything a 0.75 m pulse resolves.
constexpr double kSolidOnBoundaryM = 1e-6;

}  // namespace

double fog_extinction_per_m(double visibility_m) { return kKoschmieder / visibility_m; }

double fog_transmission(double optical_depth) { return std::exp(-2.0 * optical_depth); }

double volume_echo_energy(double extinction_per_m, double backscatter_ratio_sr,
                          double pulse_length_m, double optical_depth, double air_transmission) {
  return std::numbers::pi * backscatter_ratio_sr * extinction_per_m * pulse_length_m *
         fog_transmission(optical_depth) * air_transmission;
}

double volume_busy_length_m(double echo_energy, double threshold, double extinction_per_m,
                            double air_extinction_per_m) {
  if (threshold <= 0.0) return std::numeric_limits<double>::infinity();
  return std::log(echo_energy / threshold) / (2.0 * (extinction_per_m + air_extinction_per_m));
}

WeatherMedia::WeatherMedia(std::vector<FogVolume> fog, double backscatter_ratio,
                           std::uint32_t first, const ReceiverParams& receiver)
    : volumes(std::move(fog)),
      backscatter_ratio_sr(backscatter_ratio),
      first_object(first),
      constant_air(owsim::extinction_per_m(receiver.atmosphere) == 0.0) {
  if (volumes.size() > kMaxFogVolumes) {
    throw Error("weather.fog: at most " + std::to_string(kMaxFogVolumes) + " volumes, got " +
                std::to_string(volumes.size()));
  }
  for (const FogVolume& volume : volumes) {
    const double alpha = fog_extinction_per_m(volume.visibility_m);
    extinction_per_m.push_back(alpha);
    const double echo =
        volume_echo_energy(alpha, backscatter_ratio_sr, receiver.min_return_separation_m, 0.0,
                           two_way_transmission(receiver.atmosphere, 0.0));
    entry_echo.push_back(echo);
    entry_busy_m.push_back(echo >= receiver.threshold
                               ? volume_busy_length_m(echo, receiver.threshold, alpha, 0.0)
                               : 0.0);
  }
}

MediumPath::MediumPath(const WeatherMedia& media, const PulseRay& ray, double end_m,
                       const ReceiverParams& receiver) {
  // Every volume's stretch of the path, then the breakpoints between which α is constant.
  std::array<double, kMaxFogVolumes> enter;  // plain arrays: no per-pulse zeroing
  std::array<double, kMaxFogVolumes> exit;
  std::array<bool, kMaxFogVolumes> crossed;
  std::array<double, 2 * kMaxFogVolumes> cuts;
  std::size_t cut_count = 0;
  for (std::size_t v = 0; v < media.volumes.size(); ++v) {
    const auto interval = path_interval(media.volumes[v], ray.origin_enu_m, ray.dir_enu, end_m);
    crossed[v] = interval.has_value();
    if (!interval) continue;
    enter[v] = interval->enter_m;
    exit[v] = interval->exit_m;
    cuts[cut_count++] = interval->enter_m;
    cuts[cut_count++] = interval->exit_m;
  }
  if (cut_count == 0) return;  // clear air all the way
  if (cut_count == 2) {        // one volume on the path: one segment
    const auto v = static_cast<std::size_t>(
        std::find(crossed.begin(),
                  crossed.begin() + static_cast<std::ptrdiff_t>(media.volumes.size()), true) -
        crossed.begin());
    segments_[segment_count_++] =
        Segment{enter[v], exit[v], media.extinction_per_m[v], static_cast<std::uint32_t>(v)};
    find_runs(media, receiver, end_m);
    return;
  }
  std::sort(cuts.begin(), cuts.begin() + static_cast<std::ptrdiff_t>(cut_count));
  for (std::size_t i = 0; i + 1 < cut_count; ++i) {
    const double begin = cuts[i];
    const double end = cuts[i + 1];
    if (!(end > begin)) continue;
    Segment segment{begin, end, 0.0, 0};
    double densest = 0.0;
    for (std::size_t v = 0; v < media.volumes.size(); ++v) {
      if (!crossed[v] || enter[v] > begin || exit[v] < end) continue;
      segment.extinction_per_m += media.extinction_per_m[v];
      if (media.extinction_per_m[v] > densest) {
        densest = media.extinction_per_m[v];
        segment.volume = static_cast<std::uint32_t>(v);
      }
    }
    if (segment.extinction_per_m > 0.0) segments_[segment_count_++] = segment;
  }
  find_runs(media, receiver, end_m);
}

double MediumPath::optical_depth(double range_m) const {
  double depth = 0.0;
  for (std::size_t i = 0; i < segment_count_ && segments_[i].begin_m < range_m; ++i) {
    const Segment& s = segments_[i];
    depth += s.extinction_per_m * (std::min(s.end_m, range_m) - s.begin_m);
  }
  return depth;
}

void MediumPath::find_runs(const WeatherMedia& media, const ReceiverParams& receiver,
                           double end_m) {
  const double air_extinction = extinction_per_m(receiver.atmosphere);
  const double threshold = receiver.threshold;
  double depth = 0.0;  // τ at the current segment's start
  bool busy = false;   // the receiver is held by the last run up to the previous segment's end
  double previous_end = 0.0;
  VolumeRun* current = nullptr;  // the run holding the receiver (null when past kMaxVolumeRuns)
  for (std::size_t i = 0; i < segment_count_; ++i) {
    const Segment& s = segments_[i];
    if (busy && s.begin_m > previous_end) busy = false;  // a stretch of clear air: no echo there
    // Entering one volume from clear air (the common case) costs no exp or log.
    const bool entry = media.constant_air && depth == 0.0 &&
                       s.extinction_per_m == media.extinction_per_m[s.volume];
    const double echo =
        entry ? media.entry_echo[s.volume]
              : volume_echo_energy(s.extinction_per_m, media.backscatter_ratio_sr,
                                   receiver.min_return_separation_m, depth,
                                   two_way_transmission(receiver.atmosphere, s.begin_m));
    if (echo >= threshold) {
      if (!busy) {
        current = run_count_ < runs_.size() ? &runs_[run_count_++] : nullptr;
        if (current != nullptr) {
          current->range_m = s.begin_m;
          current->energy_rel = echo;
          current->object = media.first_object + s.volume;
        }
      }
      const double above_until =
          s.begin_m +
          (entry ? media.entry_busy_m[s.volume]
                 : volume_busy_length_m(echo, threshold, s.extinction_per_m, air_extinction));
      busy = above_until >= s.end_m;
      // The medium's own boundary ends the busy interval; the solid that ends the path does not:
      // met while the echo is still above the threshold, it merges into the volume's return (no
      // new leading edge) and is hidden with what lies inside the interval (SENSOR-SPEC §10).
      // A solid on the medium's boundary (a fog box or layer standing on the ground) is met
      // inside it, whichever of its two ranges rounding puts first.
      const bool ends_at_solid = s.end_m >= end_m - kSolidOnBoundaryM;
      if (current != nullptr) {
        current->busy_end_m = ends_at_solid ? above_until : std::min(above_until, s.end_m);
      }
    } else {
      busy = false;
    }
    depth += s.extinction_per_m * (s.end_m - s.begin_m);
    previous_end = s.end_m;
  }
}

std::size_t apply_weather(const WeatherMedia& media, const PulseRay& ray, double end_m,
                          const ReceiverParams& receiver, std::span<Candidate> buffer,
                          std::size_t count, PathBusyIntervals* busy) {
  const MediumPath path(media, ray, end_m, receiver);
  if (busy != nullptr) {
    busy->count = path.runs().size();
    for (std::size_t r = 0; r < busy->count; ++r) {
      busy->intervals[r] = BusyInterval{path.runs()[r].range_m, path.runs()[r].busy_end_m};
    }
  }
  if (path.clear()) return count;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    Candidate c = buffer[i];
    const bool hidden =
        std::any_of(path.runs().begin(), path.runs().end(), [&](const VolumeRun& run) {
          return c.range_m >= run.range_m && c.range_m < run.busy_end_m;
        });
    if (hidden) continue;
    c.energy_rel *= fog_transmission(path.optical_depth(c.range_m));
    buffer[kept++] = c;
  }
  const std::span<const VolumeRun> runs = path.runs();
  const std::size_t added = std::min(runs.size(), buffer.size() - kept);
  for (std::size_t r = 0; r < added; ++r) buffer[kept + r] = runs[r].candidate();
  return kept + added;
}

std::span<Candidate> weathered_candidates(const WeatherMedia& media, const PulseRay& ray,
                                          const PulseCandidates& met,
                                          const ReceiverParams& receiver, WeatherCandidates& buffer,
                                          PathBusyIntervals* busy) {
  std::size_t hard = 0;
  if (met.wires().empty()) {
    if (met.has_solid()) buffer[hard++] = met.solid();  // most pulses: no gathering
  } else {
    hard = met.gather(buffer).size();
  }
  const double end_m = met.has_solid() ? met.solid().range_m : timeout_range_m(receiver.counter);
  return {buffer.data(), apply_weather(media, ray, end_m, receiver, buffer, hard, busy)};
}

}  // namespace owsim
