#pragma once
// Reads a scenario file (INTERFACE.md "Scenario file", YAML) into a validated Scenario
// (io/scenario/scenario.hpp). Every SENSOR-SPEC constant a scenario may override is read under its
// documented name; every key not read is an error (io/scenario/yaml_reader.hpp), so is every bad
// value. The whole scenario is checked at load — the sensor (validate(ScanParams),
// validate(ReceiverParams)), the origin, every position, every span (build_span: a sag above its
// supports is caught here), the forest, the terrain grid — so nothing fails later, mid-flight.
//
// Errors: one owsim::Error line "<file>:<line>: <dotted key path>: <problem>", e.g.
//   "flight.yaml:31: scene.spans[1].conductor.diamter_mm: unknown key 'diamter_mm' in
//    scene.spans[1].conductor (did you mean 'diameter_mm'?)".
//
// Positions (`at`, `from`, `to`, waypoints) are written in one of three forms and resolved to
// local ENU through LocalFrame(origin):
//   {e, n, u}                              local metres
//   {lat, lon, h}                          WGS-84 degrees, ellipsoidal height in metres
//   {utm: "32U 634000 5394000", h}         UTM/UPS (geometry/utm.hpp parse_utm)
// Waypoints need the height (u or h). Poles and trees take it when given (the base's height) and
// stand on the terrain otherwise. Span supports stand on the terrain always and take no height
// (support_heights_m sets it). A lat/lon or UTM position without h is the point at that latitude
// and longitude on the terrain, found by iterating its ellipsoidal height (to 1 µm).
// Relative paths (trajectory.file, scene.terrain.grid) are resolved against the scenario
// file's folder.
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "io/scenario/scenario.hpp"

namespace owsim {

// The east/north positions of a recorded trajectory (trajectory.file), which io/trajectory reads
// (it depends on this module): with it, a DEM under a recorded flight is read for the flight's
// reach only and checked to cover it; without it (empty), such a DEM is read whole.
using RecordedTrack =
    std::function<std::vector<Eigen::Vector2d>(const Scenario&, const LocalFrame&)>;

// Reads and validates a scenario file.
[[nodiscard]] Scenario load_scenario(const std::filesystem::path& path,
                                     const RecordedTrack& recorded_track = {});

// The same from text in memory: `path` names it in errors, gives the default name (its stem)
// and anchors relative paths; the file need not exist.
[[nodiscard]] Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& path,
                                          const RecordedTrack& recorded_track = {});

}  // namespace owsim
