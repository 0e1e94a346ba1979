#pragma once
// A detector's output matched to the objects of a flight (docs/evidence.md "Scoring a detector"),
// as `owsim score` and `owsim pd` / `owsim roc --detections` share it: a detection within the gate
// of an object's surface (evaluation/object_distance.hpp) is a hit on the nearest such object,
// else a false alarm; and where each flight's detections file is.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "evaluation/object_grid.hpp"
#include "evaluation/truth_table.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/scenario/scenario.hpp"

namespace owsim {

struct ObjectHit {
  std::uint32_t object = 0;  // named object index (geometry/scene.hpp)
  double distance_m = 0.0;   // to its surface
};

// owsim::Error naming --gate-m unless 0 < gate_m ≤ 1000 m.
void validate_gate_m(double gate_m);

class DetectionMatcher {
 public:
  // `scene` must outlive this. Throws owsim::Error for a gate validate_gate_m refuses.
  DetectionMatcher(const Scene& scene, double gate_m);
  // The nearest object whose surface is within the gate of `enu_m`; none: a false alarm.
  [[nodiscard]] std::optional<ObjectHit> hit(const Eigen::Vector3d& enu_m);

 private:
  const Scene& scene_;
  ObjectGrid grid_;
  double gate_m_;
  std::vector<std::uint32_t> candidates_;
};

// The warning class the source's rules give an object of `object_class` (DETECTION-SPEC §2): wire,
// pole, tree — and tree for a building (the source's TREE: "trees, houses, towers, woods, hills");
// empty for the ground and anything else no warning is meant for.
[[nodiscard]] std::string_view expected_warning_class(std::string_view object_class);

// What a flight flew, as the scoring reads it back from its folder: the scenario (scenario.yaml,
// which runs of this owsim write) and its scene. Throws owsim::Error naming the file.
struct FlownScene {
  Scenario scenario;
  LocalFrame frame;
  Scene scene;
};
[[nodiscard]] FlownScene load_flown_scene(const CampaignFlight& flight);

// The detections file of each flight of `folder` (a run folder or a sweep folder), from the
// option `detections`: for a run, a file, or a folder holding detections.csv (the run folder
// itself: what output `detections` wrote); for a sweep, a folder of <member>.csv files, or the
// sweep folder itself (each member's own detections.csv). Throws owsim::Error naming the option
// or the missing file.
[[nodiscard]] std::vector<std::filesystem::path> detections_files(
    const std::filesystem::path& folder, std::span<const CampaignFlight> flights,
    const std::filesystem::path& detections);

}  // namespace owsim
