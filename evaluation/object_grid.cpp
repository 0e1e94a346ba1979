#include "evaluation/object_grid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr double kMinCellM = 250.0;    // about a fifth of the counter's timeout range
constexpr double kMaxCells = 1 << 20;  // the grid's cells, at most (4 MB of starts)

Eigen::AlignedBox3d object_box(const Scene& scene, std::size_t object) {
  Eigen::AlignedBox3d box;
  if (object < scene.conductors.size()) {
    for (const Eigen::Vector3d& point : scene.conductors[object].points_enu_m) box.extend(point);
  } else if (object < scene.conductors.size() + scene.cylinders.size()) {
    const Cylinder& cylinder = scene.cylinders[object - scene.conductors.size()];
    const Eigen::Vector3d corner(cylinder.radius_m, cylinder.radius_m, 0.0);
    box.extend(cylinder.base_enu_m - corner);
    box.extend(cylinder.base_enu_m + corner + Eigen::Vector3d(0, 0, cylinder.height_m));
  } else {
    const MeshObject& mesh =
        scene.meshes[object - scene.conductors.size() - scene.cylinders.size()];
    for (const Eigen::Vector3d& vertex : mesh.mesh.vertices) box.extend(vertex);
  }
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  return box;
}

}  // namespace

ObjectGrid::ObjectGrid(const Scene& scene) {
  const std::size_t count = named_object_count(scene);
  if (count > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("more scene objects than an object index holds");
  }
  spheres_.resize(count);
  cells_.resize(count);
  Eigen::AlignedBox2d extent;
  for (std::size_t object = 0; object < count; ++object) {
    const Eigen::AlignedBox3d box = object_box(scene, object);
    spheres_[object] = {box.center(), 0.5 * box.diagonal().norm()};
    extent.extend(box.min().head<2>());
    extent.extend(box.max().head<2>());
  }
  if (count == 0) return;
  const Eigen::Vector2d size = extent.sizes();
  cell_m_ = std::max(kMinCellM, std::sqrt(size.x() * size.y() / kMaxCells));
  cell_m_ = std::max({cell_m_, size.x() / 4096.0, size.y() / 4096.0});
  west_m_ = extent.min().x();
  south_m_ = extent.min().y();
  cells_x_ = static_cast<int>(size.x() / cell_m_) + 1;
  cells_y_ = static_cast<int>(size.y() / cell_m_) + 1;
  const auto cell_of = [&](double value, double low, int cells) {
    return std::clamp(static_cast<int>(std::floor((value - low) / cell_m_)), 0, cells - 1);
  };
  for (std::size_t object = 0; object < count; ++object) {
    const Sphere& s = spheres_[object];
    cells_[object] = {cell_of(s.centre.x() - s.radius_m, west_m_, cells_x_),
                      cell_of(s.centre.y() - s.radius_m, south_m_, cells_y_),
                      cell_of(s.centre.x() + s.radius_m, west_m_, cells_x_),
                      cell_of(s.centre.y() + s.radius_m, south_m_, cells_y_)};
  }
  const auto total = static_cast<std::size_t>(cells_x_) * static_cast<std::size_t>(cells_y_);
  cell_start_.assign(total + 1, 0);
  const auto for_cells = [&](const Cells& c, const auto& visit) {
    for (int y = c.y0; y <= c.y1; ++y) {
      for (int x = c.x0; x <= c.x1; ++x) {
        visit(static_cast<std::size_t>(y) * static_cast<std::size_t>(cells_x_) +
              static_cast<std::size_t>(x));
      }
    }
  };
  for (const Cells& c : cells_) for_cells(c, [&](std::size_t cell) { ++cell_start_[cell + 1]; });
  for (std::size_t cell = 0; cell < total; ++cell) cell_start_[cell + 1] += cell_start_[cell];
  cell_objects_.resize(cell_start_.back());
  std::vector<std::uint32_t> filled(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t object = 0; object < count; ++object) {
    for_cells(cells_[object], [&](std::size_t cell) {
      cell_objects_[filled[cell]++] = static_cast<std::uint32_t>(object);
    });
  }
}

void ObjectGrid::objects_near(double east_m, double north_m, double reach_m,
                              std::vector<std::uint32_t>& out) const {
  for_cells_near(east_m, north_m, reach_m, [&](int x, int y, int x0, int y0, std::uint32_t object) {
    const Cells& c = cells_[object];
    // Once per object: in the first cell of its overlap with the queried square.
    if (x == std::max(x0, c.x0) && y == std::max(y0, c.y0)) out.push_back(object);
  });
}

void ObjectGrid::objects_in_cells_near(double east_m, double north_m, double reach_m,
                                       std::vector<std::uint32_t>& out) const {
  for_cells_near(east_m, north_m, reach_m,
                 [&](int, int, int, int, std::uint32_t object) { out.push_back(object); });
}

}  // namespace owsim
