#pragma once
// A new scenario around a recorded trajectory (`owsim studio TRAJECTORY`, docs/studio.md): the
// format from the file's name (.log ArduPilot, .csv owsim CSV, .out/.sbet SBET, else HellSim),
// the local origin at the first record's position on the lowest height flown (so the flat
// ground, u = 0, is the lowest point of the flight: a recorded flight starts and ends on the
// ground), the first 10 s selected, the default sensor, and an empty scene. Plain YAML text,
// written as a user would.
#include <filesystem>
#include <string>

namespace owsim::studio {

// `trajectory_name` is written as given (relative to the scenario's folder); `trajectory_file`
// is read. Throws owsim::Error naming the file for a trajectory that cannot be read.
[[nodiscard]] std::string new_scenario_yaml(const std::filesystem::path& trajectory_file,
                                            const std::string& trajectory_name);

// A new scenario with a planned flight (`owsim studio` without input): a 60 s straight leg at
// 40 m/s, 100 m above flat ground at INTERFACE.md's example origin, the default sensor, an empty
// scene — to be edited on the map (the origin and waypoints are its keys).
[[nodiscard]] std::string new_planned_scenario_yaml(const std::string& name);

// The format key a trajectory file's name implies.
[[nodiscard]] std::string trajectory_format_of(const std::filesystem::path& file);

}  // namespace owsim::studio
