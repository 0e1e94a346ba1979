#pragma once
// The scenario's trajectory as a PoseSource (SENSOR-SPEC §5): a recorded file (HellSim, CSV,
// SBET) read and converted to the local frame, or the built-in waypoint generator; then the
// smoothing, heading handling and IRS error model the scenario asks for.
#include "geometry/geodetic_frame.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {

// The raw track of the scenario's trajectory source, in the scenario's local frame.
[[nodiscard]] NavTrack load_nav_track(const Scenario& scenario, const LocalFrame& frame);

// The spline trajectory the simulation samples. A planned (waypoint) track is not smoothed: it
// is already exact; a recorded one gets the scenario's Savitzky–Golay setting.
[[nodiscard]] Trajectory load_trajectory(const Scenario& scenario, const LocalFrame& frame);

}  // namespace owsim
