#pragma once
// scenario.yaml in a run folder (INTERFACE.md "Ground truth and detection evidence"): the scenario
// as it was flown, so `owsim view`, `owsim pd` and `owsim score` need no --scenario, and `owsim run
// scenario.yaml` flies the same frames again. The scenario's own YAML with the run's overrides
// written in (seed, range noise off, the duration of the frames flown) and every file it names
// (trajectory.file, scene.terrain.grid / dem, scene.meshes[].file, scene.power_lines[].file) made
// absolute, so the copy works from any folder. Comments are not kept; keys keep their order.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace owsim {

struct FlownOverrides {
  std::uint64_t seed = 0;
  bool no_noise = false;
  std::optional<double> duration_s;  // set when the run chose its frames (--frames, --duration)
};

// The YAML text of the scenario `yaml`, read from (or anchored at) `path`, as flown. Throws
// owsim::Error naming `path` if the text is not a YAML map.
[[nodiscard]] std::string scenario_as_flown(std::string_view yaml,
                                            const std::filesystem::path& path,
                                            const FlownOverrides& overrides);

}  // namespace owsim
