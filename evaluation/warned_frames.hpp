#pragma once
// Warnings as detection evidence (`owsim pd` and `owsim roc` with --detections, DETECTION-SPEC §5
// "system-level evidence", docs/evidence.md "Warning-level Pd"): each row of a flight's detections
// file is matched to the objects (evaluation/detection_match.hpp) and placed in the frame its time
// falls in; an object is *warned* in a frame when a row of its expected class (wire, pole, tree; a
// building's is tree) hit it there. The target's truth rows then count warned frames where they
// counted returns, so `owsim pd`'s windows and trials are the warning's: a window is detected when
// at least K (--returns, default 1) of its frames warned of the target.
// A *false warning* is a track none of whose rows hit an object (a row without a track: itself),
// counted once per flight, so an hour's false warnings are what a pilot would have been shown.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "evaluation/flight_facts.hpp"
#include "evaluation/pd_target.hpp"
#include "evaluation/truth_table.hpp"

namespace owsim {

// A flight's warnings, or several flights' summed.
struct WarningTally {
  std::uint64_t rows = 0;
  std::uint64_t tracks = 0;          // distinct tracks (a row without a track: one)
  std::uint64_t false_warnings = 0;  // of those, the ones that never hit an object
  double hours = 0.0;                // the flights' (frames × frame period)
  [[nodiscard]] double false_warnings_per_hour() const {
    return hours > 0.0 ? static_cast<double>(false_warnings) / hours : 0.0;
  }
  WarningTally& operator+=(const WarningTally& other);
};

struct FlightWarnings {
  // Object id → the frames a warning of its expected class hit it in (ascending, each once).
  std::unordered_map<std::string, std::vector<std::int64_t>> warned_frames;
  WarningTally tally;
};

// The warnings of `flight` in `detections` (a detections file, checked as `owsim score` checks
// it), matched with `gate_m`. Throws owsim::Error naming the file, line and column.
[[nodiscard]] FlightWarnings read_flight_warnings(const CampaignFlight& flight,
                                                  const FlightFacts& facts,
                                                  const std::filesystem::path& detections,
                                                  double gate_m);

// Each row of `tracks` counts the warnings instead of the returns: 1 in a frame that warned of its
// object, else 0.
void count_warned_frames(const FlightWarnings& warnings, std::span<ObjectTrack> tracks);

// --detections of `owsim pd` and `owsim roc`: each flight of `folder` (`flights`, with the target's
// `tracks` read from them) has its detections file found (detection_match.hpp detections_files),
// read and matched with `gate_m` (in (0, 1000] m, else owsim::Error naming --gate-m), and its
// tracks' rows made to count warned frames. The tallies by flight.
[[nodiscard]] std::vector<WarningTally> count_flights_warnings(
    const std::filesystem::path& folder, std::span<const CampaignFlight> flights,
    std::span<FlightTracks> tracks, const std::filesystem::path& detections, double gate_m);

}  // namespace owsim
