#pragma once
// Fog and cloud (SENSOR-SPEC §10): the extinction of every echo by the path through the media, the
// media's own echo, and the busy interval it holds the receiver for. Single scattering; pure.
//
// Along one pulse's central ray the volumes (geometry/fog_volume.hpp) cut the path into segments
// of constant total extinction α (overlapping volumes add up). The optical depth τ(R) = ∫₀ᴿ α ds
// attenuates every echo by exp(−2τ(R)) on top of T_atm. Inside a medium the volume echo is
//   e_vol(s) = π · κ · α(s) · L · exp(−2τ(s)) · T_atm(s),
// κ the backscatter-to-extinction ratio, L = c·τ_pulse/2 the medium length one pulse sees at once
// (the receiver's min_return_separation_m, 0.75 m). It falls along a segment, so it first reaches
// the threshold at a segment's start; from there the receiver is busy until e_vol drops below the
// threshold (or the medium ends): one volume candidate at the start with that energy, and hard
// echoes inside the busy interval dropped. The volume is the one of highest α there (the first
// listed on ties).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/fog_volume.hpp"
#include "sensor/pulse_candidates.hpp"
#include "sensor/receiver.hpp"

namespace owsim {

// α = 3.912 / V in 1/m (Koschmieder, 2 % contrast)  (SENSOR-SPEC §10 media)
[[nodiscard]] double fog_extinction_per_m(double visibility_m);
// exp(−2τ): the two-way transmission of an optical depth τ  (SENSOR-SPEC §10 extinction)
[[nodiscard]] double fog_transmission(double optical_depth);
// π · κ · α · L · exp(−2τ) · T_atm  (SENSOR-SPEC §10 volume echo)
[[nodiscard]] double volume_echo_energy(double extinction_per_m, double backscatter_ratio_sr,
                                        double pulse_length_m, double optical_depth,
                                        double air_transmission);
// How far past a point of echo e0 ≥ threshold the echo stays above it inside one medium of
// extinction α, with the air's own extinction σ: ln(e0 / threshold) / (2 (α + σ))
// (SENSOR-SPEC §10 detection of a volume); infinite for a zero threshold
[[nodiscard]] double volume_busy_length_m(double echo_energy, double threshold,
                                          double extinction_per_m, double air_extinction_per_m);

// The scenario's media, prepared once for one receiver: each volume with its α, and the object
// index of the first volume (its returns' `object`; the others follow in order). In air of
// constant transmission (no atmosphere.visibility_km) the echo where a ray enters a volume from
// clear air and how long it keeps the receiver busy are the same on every pulse: kept here.
struct WeatherMedia {
  std::vector<FogVolume> volumes;
  std::vector<double> extinction_per_m;
  double backscatter_ratio_sr = 0.0154;  // κ (key weather.backscatter_ratio_sr)
  std::uint32_t first_object = 0;
  bool constant_air = true;          // T_atm does not depend on the range
  std::vector<double> entry_echo;    // constant_air: the echo at an entry from clear air
  std::vector<double> entry_busy_m;  // constant_air: how long that echo stays above threshold

  WeatherMedia() = default;
  WeatherMedia(std::vector<FogVolume> fog, double backscatter_ratio_sr, std::uint32_t first_object,
               const ReceiverParams& receiver);
  [[nodiscard]] bool empty() const { return volumes.empty(); }
};

inline constexpr std::size_t kMaxFogVolumes = 32;
inline constexpr int kMaxVolumeRuns = 4;

// One volume candidate and the end of the interval it keeps the receiver busy. Plain fields, no
// initialisers: a path holds kMaxVolumeRuns of them for every pulse and fills what it uses.
struct VolumeRun {
  double range_m;     // where the echo first reaches the threshold
  double energy_rel;  // the echo there
  double busy_end_m;
  std::uint32_t object;
  [[nodiscard]] Candidate candidate() const {
    return Candidate{range_m, energy_rel, 0.0, object,
                     static_cast<std::uint8_t>(SurfaceClass::fog)};
  }
};

// One pulse's path through the media up to `end_m` (the first solid hit, or the timeout range),
// and the volume candidates on it as the receiver `receiver` sees them.
class MediumPath {
 public:
  MediumPath(const WeatherMedia& media, const PulseRay& ray, double end_m,
             const ReceiverParams& receiver);
  // τ(R) = ∫₀ᴿ α ds along the ray
  [[nodiscard]] double optical_depth(double range_m) const;
  // The volume candidates along the path, nearest first (at most kMaxVolumeRuns).
  [[nodiscard]] std::span<const VolumeRun> runs() const { return {runs_.data(), run_count_}; }
  // Whether the path meets any medium at all.
  [[nodiscard]] bool clear() const { return segment_count_ == 0; }

 private:
  // Plain members left uninitialised: a path is built for every pulse, and only the first
  // segment_count_ / run_count_ entries are ever read.
  struct Segment {
    double begin_m;
    double end_m;
    double extinction_per_m;
    std::uint32_t volume;
  };
  // `end_m`: where the path ends (the solid, or the timeout range).
  void find_runs(const WeatherMedia& media, const ReceiverParams& receiver, double end_m);
  std::array<Segment, 2 * kMaxFogVolumes + 1> segments_;
  std::size_t segment_count_ = 0;
  std::array<VolumeRun, kMaxVolumeRuns> runs_;
  std::size_t run_count_ = 0;
};

// The busy intervals of one pulse's path (SENSOR-SPEC §10, §11: they swallow false triggers too).
struct PathBusyIntervals {
  std::array<BusyInterval, kMaxVolumeRuns> intervals;
  std::size_t count = 0;
  [[nodiscard]] std::span<const BusyInterval> span() const { return {intervals.data(), count}; }
};

// SENSOR-SPEC §10 for one pulse: the `count` hard candidates at the front of `buffer` are
// attenuated by the path through the media and dropped inside a busy interval, and the volume
// candidates are appended; returns the new count (buffer.size() must leave kMaxVolumeRuns spare).
// `busy`, when given, receives the path's busy intervals (decided on the noiseless echo).
[[nodiscard]] std::size_t apply_weather(const WeatherMedia& media, const PulseRay& ray,
                                        double end_m, const ReceiverParams& receiver,
                                        std::span<Candidate> buffer, std::size_t count,
                                        PathBusyIntervals* busy = nullptr);

// Room for what one pulse hands the receiver in weather: its wires, its solid hit, the volumes'.
using WeatherCandidates = std::array<Candidate, PulseCandidates::kMaxWires + 1 + kMaxVolumeRuns>;
// What the receiver sees of a pulse that met `met` along `ray`: its candidates (gather) through the
// media up to its solid hit, or the timeout range when it has none  (SENSOR-SPEC §10)
[[nodiscard]] std::span<Candidate> weathered_candidates(
    const WeatherMedia& media, const PulseRay& ray, const PulseCandidates& met,
    const ReceiverParams& receiver, WeatherCandidates& buffer, PathBusyIntervals* busy = nullptr);

}  // namespace owsim
