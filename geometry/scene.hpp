#pragma once
// The scene the engine traces (SENSOR-SPEC §6, DESIGN.md "Engine decisions"): conductors as
// polylines sampled from their catenaries, poles and trees as vertical cylinders, buildings and
// lattice towers as triangle meshes, and the terrain. Plain values in local ENU metres from the
// scenario origin; the scenario loader fills it (geometry/span.hpp, geometry/forest.hpp), the
// engine only reads it.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/fog_volume.hpp"
#include "geometry/terrain.hpp"
#include "geometry/triangle_mesh.hpp"

namespace owsim {

// What a return hit, as the detector classes it (SENSOR-SPEC §6, ch. 1). The codes are points.csv's
// class codes and the C API's OWSIM_CLASS_*: new classes are added at the end.
// fog: the echo of a fog or cloud volume (SENSOR-SPEC §10); noise: a false return, the receiver's
// noise crossing the threshold with no echo (SENSOR-SPEC §11), no object.
enum class SurfaceClass : std::uint8_t { wire, pole, tree, ground, building, fog, noise };

inline constexpr std::size_t kSurfaceClassCount = 7;
inline constexpr std::array<SurfaceClass, kSurfaceClassCount> kSurfaceClasses = {
    SurfaceClass::wire,     SurfaceClass::pole, SurfaceClass::tree, SurfaceClass::ground,
    SurfaceClass::building, SurfaceClass::fog,  SurfaceClass::noise};

// The code that stands for "class unknown" wherever a class is a byte (a decoded return, Frame
// returns, the PLY class, the report page).
inline constexpr std::uint8_t kUnknownSurface = 255;

// "wire", "pole", "tree", "ground", "building", "fog", "noise" (the `class` column of INTERFACE.md)
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
    case SurfaceClass::building:
      return "building";
    case SurfaceClass::fog:
      return "fog";
    case SurfaceClass::noise:
      return "noise";
  }
  return "ground";
}

[[nodiscard]] constexpr std::optional<SurfaceClass> surface_class_from_string(
    std::string_view name) {
  for (const SurfaceClass surface : kSurfaceClasses) {
    if (name == to_string(surface)) return surface;
  }
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

// A placed triangle mesh (a building, a lattice tower): its triangles in local ENU metres. The
// central ray stops on it like on the ground; incidence comes from the triangle's normal.
struct MeshObject {
  std::string id;
  SurfaceClass surface = SurfaceClass::building;  // building, pole or tree
  TriangleMesh mesh;
  double reflectivity = 0.3;
};

struct Scene {
  std::vector<Conductor> conductors;
  std::vector<Cylinder> cylinders;
  std::vector<MeshObject> meshes;
  Terrain terrain;
  std::vector<FogVolume> fog;  // SENSOR-SPEC §10 media: not traced, met along each ray exactly
  double fog_backscatter_ratio_sr =
      0.0154;  // κ of SENSOR-SPEC §10 (key weather.backscatter_ratio_sr)
};

// How many objects the scene names before the terrain: conductors, cylinders and meshes.
[[nodiscard]] inline std::size_t named_object_count(const Scene& scene) {
  return scene.conductors.size() + scene.cylinders.size() + scene.meshes.size();
}

// The object index of a false return (class noise, SENSOR-SPEC §11): no object, an empty id.
inline constexpr std::uint32_t kNoObject = 0xFFFFFFFFu;

// The ground's object id (points.csv's object column); no scene object may take it.
inline constexpr std::string_view kTerrainId = "terrain";

// The id of every object a return can belong to, by object index: conductors, then cylinders,
// then meshes, then "terrain" (the order of sensor/pulse_candidates.hpp's object indices), then
// the fog volumes (fog_object_index).
[[nodiscard]] inline std::vector<std::string> object_ids(const Scene& scene) {
  std::vector<std::string> ids;
  ids.reserve(named_object_count(scene) + 1 + scene.fog.size());
  for (const Conductor& conductor : scene.conductors) ids.push_back(conductor.id);
  for (const Cylinder& cylinder : scene.cylinders) ids.push_back(cylinder.id);
  for (const MeshObject& mesh : scene.meshes) ids.push_back(mesh.id);
  ids.emplace_back(kTerrainId);
  for (const FogVolume& volume : scene.fog) ids.push_back(volume.id);
  return ids;
}

// The object index of the first fog volume; the others follow.
[[nodiscard]] inline std::uint32_t fog_object_index(const Scene& scene) {
  return static_cast<std::uint32_t>(named_object_count(scene) + 1);
}

// The class and the id of named object `object` (object < named_object_count(scene)).
[[nodiscard]] inline SurfaceClass named_object_class(const Scene& scene, std::size_t object) {
  if (object < scene.conductors.size()) return SurfaceClass::wire;
  object -= scene.conductors.size();
  if (object < scene.cylinders.size()) return scene.cylinders[object].surface;
  return scene.meshes[object - scene.cylinders.size()].surface;
}
[[nodiscard]] inline const std::string& named_object_id(const Scene& scene, std::size_t object) {
  if (object < scene.conductors.size()) return scene.conductors[object].id;
  object -= scene.conductors.size();
  if (object < scene.cylinders.size()) return scene.cylinders[object].id;
  return scene.meshes[object - scene.cylinders.size()].id;
}

}  // namespace owsim
