#pragma once
// summary.json of `owsim run` (INTERFACE.md), streamed to the file: the run facts and the totals
// first (returns by class — `noise` always, `fog` in weather — and false_returns_per_pulse, the
// noise returns over the pulses), then `objects_by_class` (per class, how many objects the scene
// has and how many the sensor saw), then `objects`, every scene object in object-index order. So a
// reader of a million-object summary finds the totals in its first kilobyte, and writing it builds
// no tree: each object's text goes straight into a buffer handed to the file a megabyte at a time.
//
// The text is nlohmann::json's with an indent of 2 (numbers and escapes as nlohmann::json writes
// them, keys of an object in alphabetical order), but for the order of the top-level keys.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "geometry/scene.hpp"
#include "io/run/flight_summary.hpp"

namespace owsim {

// Writes `path` atomically. `run_facts` (an object of scalars: scenario, seed, wall time, …)
// joins the totals. Throws owsim::Error naming the file if it cannot be written, or if `summary`
// does not tally `scene`'s objects.
void write_summary_json(const std::filesystem::path& path, const FlightSummary& summary,
                        const Scene& scene, const nlohmann::json& run_facts);

}  // namespace owsim
