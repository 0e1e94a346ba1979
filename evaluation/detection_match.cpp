#include "evaluation/detection_match.hpp"

#include <limits>
#include <string>

#include "evaluation/object_distance.hpp"
#include "geometry/error.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"

namespace owsim {

void validate_gate_m(double gate_m) {
  if (!(gate_m > 0.0 && gate_m <= 1000.0)) {
    throw input_error("--gate-m", "must lie in (0, 1000] m");
  }
}

DetectionMatcher::DetectionMatcher(const Scene& scene, double gate_m)
    : scene_(scene), grid_(scene), gate_m_(gate_m) {
  validate_gate_m(gate_m);
}

std::optional<ObjectHit> DetectionMatcher::hit(const Eigen::Vector3d& enu_m) {
  candidates_.clear();
  grid_.objects_near(enu_m.x(), enu_m.y(), gate_m_, candidates_);
  std::optional<ObjectHit> best;
  for (const std::uint32_t object : candidates_) {
    const double distance = distance_to_object_m(scene_, object, enu_m);
    if (distance <= gate_m_ && (!best || distance < best->distance_m)) {
      best = ObjectHit{object, distance};
    }
  }
  return best;
}

std::string_view expected_warning_class(std::string_view object_class) {
  if (object_class == "wire" || object_class == "pole" || object_class == "tree") {
    return object_class;
  }
  if (object_class == "building") return "tree";
  return {};
}

FlownScene load_flown_scene(const CampaignFlight& flight) {
  const std::filesystem::path scenario_file = flight.directory / "scenario.yaml";
  std::error_code error;
  if (!std::filesystem::exists(scenario_file, error)) {
    throw input_error(scenario_file.string(),
                      "missing: scoring needs the scenario the run flew (runs of this owsim "
                      "write it)");
  }
  Scenario scenario = load_scenario(scenario_file);
  const LocalFrame frame(scenario.origin);
  Scene scene = build_scene(scenario);
  return FlownScene{std::move(scenario), frame, std::move(scene)};
}

std::vector<std::filesystem::path> detections_files(const std::filesystem::path& folder,
                                                    std::span<const CampaignFlight> flights,
                                                    const std::filesystem::path& detections) {
  std::error_code error;
  const bool sweep = std::filesystem::is_regular_file(folder / "sweep.csv", error);
  const bool is_folder = std::filesystem::is_directory(detections, error);
  const bool own = is_folder && std::filesystem::equivalent(detections, folder, error);
  if (sweep && !is_folder) {
    throw input_error("--detections",
                      "a sweep folder is scored from a folder of <member>.csv files (or the sweep "
                      "folder itself, whose members wrote detections.csv)");
  }
  std::vector<std::filesystem::path> files;
  for (const CampaignFlight& flight : flights) {
    std::filesystem::path file = detections;
    if (sweep) {
      file = own ? flight.directory / "detections.csv" : detections / (flight.name + ".csv");
    } else if (is_folder) {
      file = detections / "detections.csv";
    }
    if (!std::filesystem::is_regular_file(file, error)) {
      throw input_error(file.string(),
                        sweep ? "missing: no detections file for member " + flight.name
                              : std::string("missing: no detections file"));
    }
    files.push_back(std::move(file));
  }
  return files;
}

}  // namespace owsim
