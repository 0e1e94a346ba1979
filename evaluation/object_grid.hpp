#pragma once
// The scene's named objects (conductors, poles and trees, meshes; geometry/scene.hpp object
// order) in a uniform east/north grid of their bounding boxes, so that "the objects near a point"
// costs the objects there, not the scene: what each frame's ground truth (frame_truth.hpp) and
// each detection's gate (detector_score.hpp) ask. Cells are at least 250 m, and wide enough that
// the grid holds at most ~1 M cells whatever the scene's extent. Built once; const queries are
// thread-safe.
#include <Eigen/Core>
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
  [[nodiscard]] const Sphere& sphere(std::uint32_t object) const { return spheres_[object]; }
  [[nodiscard]] std::size_t size() const { return spheres_.size(); }

 private:
  struct Cells {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the cells an object's box overlaps
  };

  std::vector<Sphere> spheres_;  // by object index
  std::vector<Cells> cells_;     // by object index
  // Cells of cell_m_; cell (x, y) holds entries [cell_start_[c], cell_start_[c + 1]).
  double west_m_ = 0.0, south_m_ = 0.0, cell_m_ = 1.0;
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> cell_objects_;
};

}  // namespace owsim
