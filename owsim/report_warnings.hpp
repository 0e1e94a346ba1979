#pragma once
// The warnings of `owsim view`'s page (issue 69): a run folder's detections.csv (output
// `detections`, or `owsim detect`) as the tracks it warned of — each track's class, where it was
// last reported (its point nearest to the aircraft then) and the frames it warned in, first to
// last (a track warns in every frame from its first report until it is dropped, so the two bound
// it). The file is read as `owsim score` reads a detections file (evaluation/detections_csv.hpp):
// every cell checked, a bad one refused in one line naming the file, line and column.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "io/scenario/scenario.hpp"

namespace owsim {

// {"tracks": [{"track", "class", "e_m", "n_m", "u_m", "first_frame", "last_frame"}, …] by first
// frame, at most `max_tracks` of them (the first ones), "tracks_total"}; `frames` is the flight's
// frame count (summary.json). A row without a track is a track of its own.
[[nodiscard]] nlohmann::json report_warnings_json(const std::filesystem::path& detections_csv,
                                                  const Scenario& scenario, std::int64_t frames,
                                                  std::size_t max_tracks);

}  // namespace owsim
