#pragma once
// The target of a detection probability — one object by id (`--target`) or every object of a
// class pooled (`--class`) — and its tracks in a campaign's flights, as `owsim pd` and `owsim roc`
// read them (docs/evidence.md).
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "evaluation/detection_probability.hpp"
#include "evaluation/truth_table.hpp"

namespace owsim {

struct PdTarget {
  std::optional<std::string> id;      // one object, by id
  std::string object_class = "wire";  // else every object of this class, pooled
  // The id, or "class:<class>".
  [[nodiscard]] std::string name() const;
  [[nodiscard]] bool matches(std::string_view object_id, std::string_view object_class) const;
};

// owsim::Error naming --class for a class owsim does not know.
void validate(const PdTarget& target);

// One flight's facts and the target's tracks in it (none when it never came within range).
struct FlightTracks {
  FlightFacts facts;
  std::vector<ObjectTrack> tracks;
};

// The flight's summary.json facts and truth.csv rows of the target (each file checked whole).
[[nodiscard]] FlightTracks read_target_tracks(const CampaignFlight& flight, const PdTarget& target);

// Every track of `flights`, each with its flight's facts; the rows stay in `flights`.
[[nodiscard]] std::vector<TargetFlight> target_flights(std::span<const FlightTracks> flights);

// owsim::Error naming --target or --class when `flights` (all of `folder`'s) hold no track.
void require_target_found(const PdTarget& target, std::span<const FlightTracks> flights,
                          const std::filesystem::path& folder);

}  // namespace owsim
