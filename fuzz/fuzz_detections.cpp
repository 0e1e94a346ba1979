// libFuzzer target: a detections file as `owsim score` reads it (evaluation/detections_csv.hpp
// read_detections_csv, the local `e_m,n_m,u_m` and the geodetic `lat_deg,lon_deg,h_m` forms alike:
// the header decides), on arbitrary bytes, for a flight of 10 to 70 s. Each detection it accepts
// must keep docs/evidence.md's bounds (a finite time within the flight ± 60 s, a position within
// 1,000 km of the origin) and is then matched as the scorer matches it (evaluation/
// detector_score.cpp): the objects near it in the ObjectGrid of a small fixed scene, its distance
// to each, and its score.csv cells. Any input must either read or throw owsim::Error; any other
// exception, a broken bound, a crash or a sanitizer report is a finding (issue 45).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "evaluation/detections_csv.hpp"
#include "evaluation/object_distance.hpp"
#include "evaluation/object_grid.hpp"
#include "fuzz/fuzz_input_file.hpp"
#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"

namespace {

// A wire, a pole and a wall near the origin.
owsim::Scene small_scene() {
  owsim::Scene scene;
  owsim::Conductor wire;
  wire.id = "wire";
  wire.radius_m = 0.01;
  wire.points_enu_m = {{0, -100, 30}, {0, 0, 25}, {0, 100, 30}};
  scene.conductors.push_back(wire);
  owsim::Cylinder pole;
  pole.id = "pole";
  pole.base_enu_m = {50, 0, 0};
  pole.radius_m = 0.5;
  pole.height_m = 20;
  scene.cylinders.push_back(pole);
  owsim::MeshObject wall;
  wall.id = "wall";
  wall.mesh.vertices = {{100, -10, 0}, {100, 10, 0}, {100, 10, 10}, {100, -10, 10}};
  wall.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes.push_back(wall);
  return scene;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const owsim::LocalFrame frame(owsim::Geodetic{48.6881, 10.8447, 450.0});
  static const owsim::Scene scene = small_scene();
  static const owsim::ObjectGrid grid(scene);
  constexpr double kGateM = 5.0;
  const std::string path = owsim::fuzz::write_input_file(data, size, ".csv");
  std::vector<std::uint32_t> candidates;
  std::string rows;
  try {
    owsim::read_detections_csv(path, {frame, 10.0, 70.0}, [&](const owsim::Detection& detection) {
      if (!(detection.time_s >= 10.0 - owsim::kDetectionTimeMarginS &&
            detection.time_s <= 70.0 + owsim::kDetectionTimeMarginS) ||
          !(detection.enu_m.norm() <= owsim::kMaxDetectionDistanceM)) {
        std::abort();  // accepted outside its bounds
      }
      candidates.clear();
      grid.objects_near(detection.enu_m.x(), detection.enu_m.y(), kGateM, candidates);
      double nearest = INFINITY;
      for (const std::uint32_t object : candidates) {
        nearest = std::fmin(nearest, owsim::distance_to_object_m(scene, object, detection.enu_m));
      }
      rows.clear();
      owsim::append_csv_fixed(rows, detection.time_s, 6);
      for (int axis = 0; axis < 3; ++axis) owsim::append_csv_fixed(rows, detection.enu_m[axis], 3);
      rows += owsim::csv_cell(detection.object_class) + owsim::csv_cell(detection.track);
      if (nearest <= kGateM) owsim::append_csv_fixed(rows, nearest, 3);
    });
  } catch (const owsim::Error&) {
  }
  return 0;
}
