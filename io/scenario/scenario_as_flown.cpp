#include "io/scenario/scenario_as_flown.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>

#include "geometry/error.hpp"

namespace owsim {
namespace {

// The file name `node` holds, made absolute against the scenario's folder.
void make_absolute(YAML::Node node, const std::filesystem::path& folder) {
  if (!node || !node.IsScalar()) return;
  const std::filesystem::path given(node.as<std::string>());
  if (given.empty()) return;
  const std::filesystem::path resolved = given.is_absolute() ? given : folder / given;
  node = std::filesystem::absolute(resolved).lexically_normal().string();
}

// A double as the shortest text that reads back to it.
std::string exact_text(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

std::string scenario_as_flown(std::string_view yaml, const std::filesystem::path& path,
                              const FlownOverrides& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml));
  } catch (const YAML::Exception& error) {
    throw input_error(path.string(), std::string("not YAML: ") + error.what());
  }
  if (!root.IsMap()) throw input_error(path.string(), "not a YAML map");
  root["seed"] = overrides.seed;
  if (overrides.no_noise) root["sensor"]["range_noise_sigma_m"] = 0;
  if (overrides.duration_s) root["trajectory"]["duration_s"] = exact_text(*overrides.duration_s);

  const std::filesystem::path folder = path.parent_path();
  if (YAML::Node trajectory = root["trajectory"]; trajectory.IsMap()) {
    make_absolute(trajectory["file"], folder);
  }
  if (YAML::Node scene = root["scene"]; scene.IsMap()) {
    if (YAML::Node terrain = scene["terrain"]; terrain.IsMap()) {
      make_absolute(terrain["grid"], folder);
      make_absolute(terrain["dem"], folder);
    }
    for (const char* list : {"meshes", "power_lines"}) {
      if (YAML::Node items = scene[list]; items.IsSequence()) {
        for (YAML::Node item : items) {
          if (item.IsMap()) make_absolute(item["file"], folder);
        }
      }
    }
  }
  YAML::Emitter out;
  out << root;
  std::string text = out.c_str();
  text += '\n';
  return text;
}

}  // namespace owsim
