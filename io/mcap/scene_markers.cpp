#include "io/mcap/scene_markers.hpp"

#include <algorithm>

namespace owsim::ros2 {
namespace {

constexpr double kMinimumLineWidthM = 0.1;

ColorRgba class_color(SurfaceClass surface) {
  switch (surface) {
    case SurfaceClass::wire:
      return {1.0F, 0.55F, 0.0F, 1.0F};
    case SurfaceClass::pole:
      return {0.55F, 0.4F, 0.25F, 1.0F};
    case SurfaceClass::tree:
      return {0.15F, 0.6F, 0.2F, 1.0F};
    case SurfaceClass::fog:
      return {0.85F, 0.85F, 0.9F, 0.25F};
    case SurfaceClass::building:
    case SurfaceClass::ground:
    case SurfaceClass::noise:
      break;
  }
  return {0.6F, 0.6F, 0.65F, 1.0F};
}

Point point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

Marker object_marker(const std::string& id, const Time& stamp, std::int32_t type,
                     SurfaceClass surface) {
  Marker marker;
  marker.header.stamp = stamp;
  marker.header.frame_id = "map";
  marker.ns = id;
  marker.text = id;
  marker.type = type;
  marker.color = class_color(surface);
  return marker;
}

}  // namespace

MarkerArray scene_markers(const Scene& scene, const Time& stamp) {
  MarkerArray array;
  array.markers.reserve(named_object_count(scene) + scene.fog.size());
  for (const Conductor& conductor : scene.conductors) {
    Marker marker = object_marker(conductor.id, stamp, Marker::kLineStrip, SurfaceClass::wire);
    marker.scale = {std::max(2 * conductor.radius_m, kMinimumLineWidthM), 0, 0};
    marker.points.reserve(conductor.points_enu_m.size());
    for (const Eigen::Vector3d& vertex : conductor.points_enu_m) {
      marker.points.push_back(point(vertex));
    }
    array.markers.push_back(std::move(marker));
  }
  for (const Cylinder& cylinder : scene.cylinders) {
    Marker marker = object_marker(cylinder.id, stamp, Marker::kCylinder, cylinder.surface);
    marker.pose.position =
        point(cylinder.base_enu_m + Eigen::Vector3d(0, 0, cylinder.height_m / 2));
    marker.scale = {2 * cylinder.radius_m, 2 * cylinder.radius_m, cylinder.height_m};
    array.markers.push_back(std::move(marker));
  }
  for (const MeshObject& mesh : scene.meshes) {
    Marker marker = object_marker(mesh.id, stamp, Marker::kTriangleList, mesh.surface);
    marker.points.reserve(3 * mesh.mesh.triangles.size());
    for (const auto& triangle : mesh.mesh.triangles) {
      for (const std::uint32_t vertex : triangle) {
        marker.points.push_back(point(mesh.mesh.vertices[vertex]));
      }
    }
    array.markers.push_back(std::move(marker));
  }
  for (const FogVolume& volume : scene.fog) {
    if (volume.shape != FogShape::box) continue;
    Marker marker = object_marker(volume.id, stamp, Marker::kCube, SurfaceClass::fog);
    marker.pose.position = point(volume.box.center());
    const Eigen::Vector3d size = volume.box.sizes();
    marker.scale = {size.x(), size.y(), size.z()};
    array.markers.push_back(std::move(marker));
  }
  return array;
}

}  // namespace owsim::ros2
