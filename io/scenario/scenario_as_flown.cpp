#include "io/scenario/scenario_as_flown.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/confined_path.hpp"
#include "io/files/output_open.hpp"

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

// The file `source` copied to `target` through an AtomicOutputFile.
void copy_input(const std::filesystem::path& source, const std::filesystem::path& target) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(source.c_str(), "rb"),
                                                           &std::fclose);
  const auto cannot = [&](int error_number) {
    return file_error(target.string(), "cannot copy the scenario's file " + source.string() +
                                           " into the run folder: " + std::strerror(error_number));
  };
  if (!in) throw cannot(errno);
  AtomicOutputFile out(target);
  std::vector<char> buffer(std::size_t{1} << 20);
  std::size_t got = 0;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), in.get())) > 0) {
    out.write(buffer.data(), got);
  }
  if (std::ferror(in.get()) != 0) throw cannot(EIO);
  out.commit();
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
    make_output_subfolders(folder, input.target.parent_path());
    // A hard link costs nothing; link() makes a new name, never following what is there.
    const std::filesystem::path partial = AtomicOutputFile::partial_path_for(target);
    clear_output_name(partial, target.string());
    if (::linkat(AT_FDCWD, input.source.c_str(), AT_FDCWD, partial.c_str(), AT_SYMLINK_FOLLOW) ==
        0) {
      if (std::rename(partial.c_str(), target.c_str()) != 0) {
        const int error_number = errno;
        ::unlink(partial.c_str());
        throw file_error(target.string(), "cannot rename " + partial.string() +
                                              " to the final name: " + std::strerror(error_number));
      }
      continue;
    }
    if (errno == EEXIST) {
      throw file_error(target.string(),
                       "cannot create " + partial.string() +
                           ": something was put in its place while owsim created it");
    }
    copy_input(input.source, target);
  }
}

}  // namespace owsim
