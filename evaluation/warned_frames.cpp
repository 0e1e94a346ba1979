#include "evaluation/warned_frames.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_set>

#include "evaluation/detection_match.hpp"
#include "evaluation/detections_csv.hpp"

namespace owsim {

WarningTally& WarningTally::operator+=(const WarningTally& other) {
  rows += other.rows;
  tracks += other.tracks;
  false_warnings += other.false_warnings;
  hours += other.hours;
  return *this;
}

FlightWarnings read_flight_warnings(const CampaignFlight& flight, const FlightFacts& facts,
                                    const std::filesystem::path& detections, double gate_m) {
  const FlownScene flown = load_flown_scene(flight);
  DetectionMatcher matcher(flown.scene, gate_m);
  const double start_s = flown.scenario.scan.start_s;
  const DetectionFlight window{flown.frame, start_s, start_s + facts.flight_s()};
  FlightWarnings out;
  out.tally.hours = facts.flight_s() / 3600.0;
  std::unordered_set<std::string> tracks, true_tracks;
  std::uint64_t untracked_false = 0, untracked = 0;
  read_detections_csv(detections, window, [&](const Detection& detection) {
    ++out.tally.rows;
    const std::optional<ObjectHit> hit = matcher.hit(detection.enu_m);
    if (detection.track.empty()) {
      ++untracked;
      if (!hit) ++untracked_false;
    } else {
      tracks.insert(detection.track);
      if (hit) true_tracks.insert(detection.track);
    }
    if (!hit) return;
    const std::string_view object_class = to_string(named_object_class(flown.scene, hit->object));
    if (detection.object_class != expected_warning_class(object_class)) return;
    // The frame the row's time falls in (a row at a frame's first pulse is that frame's).
    const double frame_s = (detection.time_s - start_s) / facts.frame_period_s;
    const auto frame = std::clamp<std::int64_t>(
        static_cast<std::int64_t>(std::floor(frame_s + 1e-6)), 0, facts.frames - 1);
    out.warned_frames[named_object_id(flown.scene, hit->object)].push_back(frame);
  });
  out.tally.tracks = tracks.size() + untracked;
  out.tally.false_warnings = tracks.size() - true_tracks.size() + untracked_false;
  for (auto& [id, frames] : out.warned_frames) {
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  }
  return out;
}

void count_warned_frames(const FlightWarnings& warnings, std::span<ObjectTrack> tracks) {
  static const std::vector<std::int64_t> kNone;
  for (ObjectTrack& track : tracks) {
    const auto found = warnings.warned_frames.find(track.id);
    const std::vector<std::int64_t>& frames =
        found == warnings.warned_frames.end() ? kNone : found->second;
    for (TruthEntry& row : track.rows) {
      row.returns = std::binary_search(frames.begin(), frames.end(), row.frame) ? 1 : 0;
    }
  }
}

std::vector<WarningTally> count_flights_warnings(const std::filesystem::path& folder,
                                                 std::span<const CampaignFlight> flights,
                                                 std::span<FlightTracks> tracks,
                                                 const std::filesystem::path& detections,
                                                 double gate_m) {
  validate_gate_m(gate_m);
  const std::vector<std::filesystem::path> files = detections_files(folder, flights, detections);
  std::vector<WarningTally> tallies;
  for (std::size_t f = 0; f < flights.size(); ++f) {
    const FlightWarnings warnings =
        read_flight_warnings(flights[f], tracks[f].facts, files[f], gate_m);
    count_warned_frames(warnings, tracks[f].tracks);
    tallies.push_back(warnings.tally);
  }
  return tallies;
}

}  // namespace owsim
