#include "evaluation/pd_target.hpp"

#include <algorithm>

#include "geometry/error.hpp"
#include "geometry/scene.hpp"

namespace owsim {

std::string PdTarget::name() const { return id ? *id : "class:" + object_class; }

bool PdTarget::matches(std::string_view object_id, std::string_view of_class) const {
  return id ? object_id == *id : of_class == object_class;
}

void validate(const PdTarget& target) {
  if (!target.id && !surface_class_from_string(target.object_class)) {
    throw input_error("--class", "unknown class '" + target.object_class +
                                     "' (expected wire, pole, tree, building)");
  }
}

FlightTracks read_target_tracks(const CampaignFlight& flight, const PdTarget& target) {
  FlightTracks tracks;
  tracks.facts = read_flight_facts(flight.directory / "summary.json");
  tracks.tracks = read_truth_csv(flight.directory / "truth.csv", tracks.facts,
                                 [&](std::string_view id, std::string_view object_class) {
                                   return target.matches(id, object_class);
                                 });
  return tracks;
}

std::vector<TargetFlight> target_flights(std::span<const FlightTracks> flights) {
  std::vector<TargetFlight> out;
  for (const FlightTracks& flight : flights) {
    for (const ObjectTrack& track : flight.tracks) out.push_back({track.rows, flight.facts});
  }
  return out;
}

void require_target_found(const PdTarget& target, std::span<const FlightTracks> flights,
                          const std::filesystem::path& folder) {
  if (std::any_of(flights.begin(), flights.end(),
                  [](const FlightTracks& flight) { return !flight.tracks.empty(); })) {
    return;
  }
  throw input_error(
      target.id ? "--target" : "--class",
      "no " + (target.id ? "object '" + *target.id + "'" : target.object_class + " object") +
          " in the ground truth of " + folder.string());
}

}  // namespace owsim
