#include "io/scenario/scenario_as_flown.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/confined_path.hpp"

namespace owsim {
namespace {

// The run folder's name for input file k (0-based) and for a file at `path` relative to it.
std::filesystem::path copy_name(std::size_t k, const std::filesystem::path& relative) {
  return std::filesystem::path("inputs") / std::to_string(k + 1) / relative;
}

// The file name `node` holds, replaced by the name of its copy in the run folder.
void name_copy(YAML::Node node, const std::filesystem::path& folder,
               const std::vector<InputFile>& input_files) {
  if (!node || !node.IsScalar()) return;
  const std::filesystem::path file = confined_file(folder, node.as<std::string>());
  for (std::size_t k = 0; k < input_files.size(); ++k) {
    if (input_files[k].file == file) {
      node = copy_name(k, file.filename()).string();
      return;
    }
  }
  throw Error(file.string() + ": a scenario file the loader did not read");
}

// A double as the shortest text that reads back to it.
std::string exact_text(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

FlownScenario scenario_as_flown(std::string_view yaml, const std::filesystem::path& path,
                                const FlownOverrides& overrides,
                                const std::vector<InputFile>& input_files) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml));
  } catch (const YAML::Exception& error) {
    throw input_error(path.string(), std::string("not YAML: ") + error.what());
  }
  if (!root.IsMap()) throw input_error(path.string(), "not a YAML map");
  root["seed"] = overrides.seed;
  if (overrides.no_noise) {
    root["sensor"]["range_noise_sigma_m"] = 0;
    root["sensor"]["receiver"]["noise"] = "off";
  }
  if (overrides.duration_s) root["trajectory"]["duration_s"] = exact_text(*overrides.duration_s);

  const std::filesystem::path folder = path.parent_path();
  if (YAML::Node trajectory = root["trajectory"]; trajectory.IsMap()) {
    name_copy(trajectory["file"], folder, input_files);
  }
  if (YAML::Node scene = root["scene"]; scene.IsMap()) {
    if (YAML::Node terrain = scene["terrain"]; terrain.IsMap()) {
      name_copy(terrain["grid"], folder, input_files);
      name_copy(terrain["dem"], folder, input_files);
    }
    for (const char* list : {"meshes", "power_lines"}) {
      if (YAML::Node items = scene[list]; items.IsSequence()) {
        for (YAML::Node item : items) {
          if (item.IsMap()) name_copy(item["file"], folder, input_files);
        }
      }
    }
  }
  YAML::Emitter out;
  out << root;
  FlownScenario flown;
  flown.yaml = out.c_str();
  flown.yaml += '\n';
  for (std::size_t k = 0; k < input_files.size(); ++k) {
    const InputFile& input = input_files[k];
    flown.inputs.push_back({input.file, copy_name(k, input.file.filename())});
    for (const std::filesystem::path& companion : input.companions) {
      flown.inputs.push_back(
          {companion, copy_name(k, companion.lexically_relative(input.file.parent_path()))});
    }
  }
  return flown;
}

void write_input_copies(const std::filesystem::path& folder, const std::vector<InputCopy>& inputs) {
  for (const InputCopy& input : inputs) {
    const std::filesystem::path target = folder / input.target;
    const std::filesystem::path partial = AtomicOutputFile::partial_path_for(target);
    std::error_code error;
    std::filesystem::create_directories(target.parent_path(), error);
    std::filesystem::remove(partial, error);
    std::filesystem::create_hard_link(input.source, partial, error);
    if (error) std::filesystem::copy_file(input.source, partial, error);
    if (!error) std::filesystem::rename(partial, target, error);
    if (error) {
      const std::string reason = error.message();
      std::filesystem::remove(partial, error);
      throw FileError(target.string() + ": cannot copy the scenario's file " +
                      input.source.string() + " into the run folder: " + reason);
    }
  }
}

}  // namespace owsim
