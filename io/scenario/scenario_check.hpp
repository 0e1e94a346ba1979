#pragma once
// The checks a Scenario (io/scenario/scenario.hpp) must pass before it is simulated, on the structs
// themselves: what the YAML loader (io/scenario/scenario_loader.hpp) checks as it reads, for a
// scenario an embedding program built in code (owsim::Simulation::from_scenario). The loader does
// not run it again (it has checked every value where it read it, with its line, and a forest is not
// drawn twice); tests/test_scenario_check.cpp holds the two to the same messages.
//
// Throws owsim::Error "<key path>: <problem>" with the scenario file's key path
// ("scene.poles[1].height_m: must be > 0, got -3"), as the loader's message after its
// "<file>:<line>: "; Simulation::from_scenario puts the scenario's name in front.
#include <string>

#include "io/scenario/scenario.hpp"

namespace owsim {

void validate_scenario(const Scenario& scenario);

// What is wrong with an object's id (empty, a '/', which owsim's own ids use, or the ground's
// "terrain"), "" when nothing: the loader and validate_scenario say the same.
[[nodiscard]] std::string object_id_problem(const std::string& id);

}  // namespace owsim
