#pragma once
// What the studio's map and profile draw of a scenario (docs/studio.md): the whole recorded or
// planned track in WGS-84 with its height above the ground, speed and the sensor's field at each
// sample; the scene's objects as built (conductors as polylines, poles and trees as circles, the
// outlines of meshes and fog volumes), so that a span given by towers and sag is drawn where
// `owsim run` puts it. JSON for the web app; built from a Simulation, so it shows exactly what the
// loader made of the YAML.
#include <nlohmann/json.hpp>

#include "owsim/simulation.hpp"

namespace owsim::studio {

// Track samples every `step_s` seconds over the trajectory's whole clock (not only the
// scenario's start_s … start_s + duration_s).
[[nodiscard]] nlohmann::json scene_view(const Simulation& simulation, double step_s = 0.25);

}  // namespace owsim::studio
