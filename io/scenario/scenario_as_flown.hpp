#pragma once
// scenario.yaml in a run folder (INTERFACE.md "Ground truth and detection evidence"): the scenario
// as it was flown, so `owsim view`, `owsim pd` and `owsim score` need no --scenario, and `owsim run
// scenario.yaml` flies the same frames again. The scenario's own YAML with the run's overrides
// written in (seed; for no_noise `sensor.range_noise_sigma_m: 0` and `sensor.receiver.noise:
// off`; the duration of the frames flown) and every file it names (trajectory.file,
// scene.terrain.grid / dem, scene.meshes[].file, scene.power_lines[].file)
// copied into the run folder as inputs/<k>/<name> (the k-th file read, with the files it pulled
// in at their places relative to it), so the run folder reads only its own tree — it is a scenario
// like any other (issue 33) — and works from any folder. Comments are not kept; keys keep their
// order.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/scenario/scenario.hpp"

namespace owsim {

struct FlownOverrides {
  std::uint64_t seed = 0;
  bool no_noise = false;
  std::optional<double> duration_s;  // set when the run chose its frames (--frames, --duration)
};

// A file the run folder holds a copy of: `target` relative to the folder.
struct InputCopy {
  std::filesystem::path source;
  std::filesystem::path target;
  friend bool operator==(const InputCopy&, const InputCopy&) = default;
};

struct FlownScenario {
  std::string yaml;
  std::vector<InputCopy> inputs;
};

// The scenario `yaml`, read from (or anchored at) `path`, as flown, with `input_files` (what the
// loader read: Scenario::input_files) as the copies its file keys now name. Throws owsim::Error
// naming `path` if the text is not a YAML map.
[[nodiscard]] FlownScenario scenario_as_flown(std::string_view yaml,
                                              const std::filesystem::path& path,
                                              const FlownOverrides& overrides,
                                              const std::vector<InputFile>& input_files);

// Places every copy in `folder` (hard links where the file system allows, else copies; a copy
// appears under its name only when complete; the folders inputs/… and the copies' temporaries are
// never followed through a link: io/files/output_open.hpp). Throws owsim::FileError naming the
// file.
void write_input_copies(const std::filesystem::path& folder, const std::vector<InputCopy>& inputs);

}  // namespace owsim
