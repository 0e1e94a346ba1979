#include "io/report/report_scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace owsim {
namespace {

// Rounded to the centimetre: the page's drawings need no more and the file stays small.
double cm(double metres) { return std::round(metres * 100.0) / 100.0; }

nlohmann::json enu(const Eigen::Vector3d& p) { return {cm(p.x()), cm(p.y()), cm(p.z())}; }

}  // namespace

nlohmann::json report_scene_json(const Scene& scene, std::size_t max_cylinders) {
  nlohmann::json wires = nlohmann::json::array();
  for (const Conductor& conductor : scene.conductors) {
    const std::vector<Eigen::Vector3d>& p = conductor.points_enu_m;
    nlohmann::json points = nlohmann::json::array();
    const std::size_t n = p.size();
    const std::size_t keep = std::min(n, kReportWireVertices);
    for (std::size_t i = 0; i < keep; ++i) {
      points.push_back(enu(p[keep == 1 ? 0 : i * (n - 1) / (keep - 1)]));
    }
    wires.push_back({{"id", conductor.id}, {"points", std::move(points)}});
  }
  nlohmann::json cylinders = nlohmann::json::array();
  const std::size_t total = scene.cylinders.size();
  const std::size_t shown = std::min(total, max_cylinders);
  for (std::size_t i = 0; i < shown; ++i) {
    const Cylinder& c = scene.cylinders[i * total / shown];
    cylinders.push_back({cm(c.base_enu_m.x()), cm(c.base_enu_m.y()), cm(c.base_enu_m.z()),
                         cm(c.height_m), cm(c.radius_m), static_cast<int>(c.surface)});
  }
  nlohmann::json meshes = nlohmann::json::array();
  for (const MeshObject& object : scene.meshes) {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& v : object.mesh.vertices) box.extend(v);
    if (box.isEmpty()) continue;
    nlohmann::json corners = enu(box.min());
    for (const auto& v : enu(box.max())) corners.push_back(v);
    meshes.push_back({{"id", object.id}, {"class", to_string(object.surface)}, {"box", corners}});
  }
  return {{"wires", std::move(wires)},
          {"cylinders", std::move(cylinders)},
          {"cylinders_total", total},
          {"meshes", std::move(meshes)}};
}

}  // namespace owsim
