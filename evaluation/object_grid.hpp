#pragma once
// The scene's named objects (conductors, poles and trees, meshes; geometry/scene.hpp object
// order) in a uniform east/north grid of their bounding boxes, so that "the objects near a point"
// costs the objects there, not the scene: what each frame's ground truth (frame_truth.hpp) and
// each detection's gate (detector_score.hpp) ask. Cells are at least 250 m, and wide enough that
// the grid holds at most ~1 M cells whatever the scene's extent. Built once; const queries are
// thread-safe.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/scene.hpp"

namespace owsim {

class ObjectGrid {
 public:
  // A bounding sphere of each object.
  struct Sphere {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius_m = 0.0;
  };

  // Throws owsim::Error for a scene of more objects than an index holds.
  explicit ObjectGrid(const Scene& scene);

  // Appends every object whose box overlaps the square of half-width `reach_m` around
  // (east, north), each once, in a fixed order.
  void objects_near(double east_m, double north_m, double reach_m,
                    std::vector<std::uint32_t>& out) const;
  // The same, but an object whose box spans several of those cells comes once per cell: for a
  // caller that marks what it is given (it saves reading every object's cell range).
  void objects_in_cells_near(double east_m, double north_m, double reach_m,
                             std::vector<std::uint32_t>& out) const;
  [[nodiscard]] const Sphere& sphere(std::uint32_t object) const { return spheres_[object]; }
  [[nodiscard]] std::size_t size() const { return spheres_.size(); }

 private:
  struct Cells {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the cells an object's box overlaps
  };

  // visit(x, y, x0, y0, object) for each entry of each cell (x, y) of the square's cells, whose
  // lowest are (x0, y0).
  template <typename Visit>
  void for_cells_near(double east_m, double north_m, double reach_m, const Visit& visit) const {
    if (spheres_.empty()) return;
    const auto cell_of = [&](double value, double low, int cells) {
      return static_cast<int>(
          std::clamp(std::floor((value - low) / cell_m_), -1.0, static_cast<double>(cells)));
    };
    const int x0 = std::max(0, cell_of(east_m - reach_m, west_m_, cells_x_));
    const int x1 = std::min(cells_x_ - 1, cell_of(east_m + reach_m, west_m_, cells_x_));
    const int y0 = std::max(0, cell_of(north_m - reach_m, south_m_, cells_y_));
    const int y1 = std::min(cells_y_ - 1, cell_of(north_m + reach_m, south_m_, cells_y_));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::size_t cell = static_cast<std::size_t>(y) * static_cast<std::size_t>(cells_x_) +
                                 static_cast<std::size_t>(x);
        for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          visit(x, y, x0, y0, cell_objects_[k]);
        }
      }
    }
  }

  std::vector<Sphere> spheres_;  // by object index
  std::vector<Cells> cells_;     // by object index
  // Cells of cell_m_; cell (x, y) holds entries [cell_start_[c], cell_start_[c + 1]).
  double west_m_ = 0.0, south_m_ = 0.0, cell_m_ = 1.0;
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> cell_objects_;
};

}  // namespace owsim
