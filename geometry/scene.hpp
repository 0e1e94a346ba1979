#pragma once
// The scene the engine traces (SENSOR-SPEC §6, DESIGN.md "Engine decisions"): conductors as
// polylines sampled from their catenaries, poles and trees as vertical cylinders, and the
// terrain. Plain values in local ENU metres from the scenario origin; the scenario loader fills
// it (geometry/span.hpp, geometry/forest.hpp), the engine only reads it.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/terrain.hpp"

namespace owsim {

// What a return hit, as the detector classes it (SENSOR-SPEC §6, ch. 1).
enum class SurfaceClass : std::uint8_t { wire, pole, tree, ground };

// "wire", "pole", "tree", "ground" (the `class` column of INTERFACE.md)
[[nodiscard]] constexpr std::string_view to_string(SurfaceClass surface) {
  switch (surface) {
    case SurfaceClass::wire:
      return "wire";
    case SurfaceClass::pole:
      return "pole";
    case SurfaceClass::tree:
      return "tree";
    case SurfaceClass::ground:
      return "ground";
  }
  return "ground";
}

[[nodiscard]] constexpr std::optional<SurfaceClass> surface_class_from_string(
    std::string_view name) {
  if (name == "wire") return SurfaceClass::wire;
  if (name == "pole") return SurfaceClass::pole;
  if (name == "tree") return SurfaceClass::tree;
  if (name == "ground") return SurfaceClass::ground;
  return std::nullopt;
}

// One wire: its catenary sampled so the polyline stays within 1 mm of the curve.
struct Conductor {
  std::string id;                             // "<span id>/<n>"
  std::vector<Eigen::Vector3d> points_enu_m;  // polyline vertices, from → to
  double radius_m = 0.01;
  double reflectivity = 0.4;  // SENSOR-SPEC §6 nominal wire reflectivity
};

// A vertical solid cylinder standing on base_enu_m (the centre of its bottom disc).
struct Cylinder {
  std::string id;
  SurfaceClass surface = SurfaceClass::pole;  // pole or tree
  Eigen::Vector3d base_enu_m = Eigen::Vector3d::Zero();
  double radius_m = 0.25;
  double height_m = 10.0;
  double reflectivity = 0.3;
};

struct Scene {
  std::vector<Conductor> conductors;
  std::vector<Cylinder> cylinders;
  Terrain terrain;
};

// The id of every object a return can belong to, by object index: conductors, then cylinders,
// then "terrain" (the order of sensor/pulse_candidates.hpp's object indices).
[[nodiscard]] inline std::vector<std::string> object_ids(const Scene& scene) {
  std::vector<std::string> ids;
  ids.reserve(scene.conductors.size() + scene.cylinders.size() + 1);
  for (const Conductor& conductor : scene.conductors) ids.push_back(conductor.id);
  for (const Cylinder& cylinder : scene.cylinders) ids.push_back(cylinder.id);
  ids.emplace_back("terrain");
  return ids;
}

}  // namespace owsim
