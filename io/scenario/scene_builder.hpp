#pragma once
// Turns a scenario's scene (io/scenario/scenario.hpp SceneSpec) into the geometry the engine traces
// (geometry/scene.hpp): every span's conductors, each its own object "<span>/<n>", and its
// support poles "<span>/pole-1", "<span>/pole-2" (geometry/span.hpp build_span, on the terrain);
// the scenario's poles and trees as placed; the forest drawn with the scenario's seed
// (geometry/forest.hpp); the terrain. Deterministic: the same scenario gives the same scene.
// Order: conductors in span then layout order; cylinders as span poles (span order), poles,
// trees, forest trees.
#include "geometry/scene.hpp"
#include "io/scenario/scenario.hpp"

namespace owsim {

// Throws owsim::Error "<scenario file>: scene.<key>: <problem>" for a scene that cannot be built
// (a scenario from load_scenario has already been checked and always builds).
[[nodiscard]] Scene build_scene(const Scenario& scenario);

}  // namespace owsim
