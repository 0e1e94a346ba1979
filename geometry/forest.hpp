#pragma once
// A forest of trees scattered over a rectangle (SENSOR-SPEC §6: trees are vertical cylinders;
// INTERFACE.md scene.forest). Tree i is drawn from its own keyed random block
// random_block({seed, frame 0, pulse i, RandomPurpose::forest_layout}): its four 32-bit words,
// each scaled to [0, 1) by 2^-32, place it uniformly in e and n and pick its height and diameter
// uniformly in their ranges. So the same seed gives the same forest on any machine, and growing
// `count` keeps the first trees unchanged. Trees stand on the terrain under their centre and
// may overlap; ids are "forest/<i>" with i = 0, 1, … (the key's pulse index).
#include <Eigen/Core>
#include <cstdint>
#include <string_view>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/terrain.hpp"

namespace owsim {

struct ForestSpec {
  int count = 0;
  Eigen::Vector2d e_range = {-500.0, 500.0};  // [min, max] east, metres
  Eigen::Vector2d n_range = {-500.0, 500.0};  // [min, max] north, metres
  double height_min_m = 8.0;
  double height_max_m = 25.0;
  double diameter_min_m = 2.0;
  double diameter_max_m = 8.0;
  double reflectivity = 0.2;
};

// The forest's trees (SurfaceClass::tree). Throws owsim::Error "<where>.<key>: …" (keys count,
// area.e, area.n, height_m, diameter_m, reflectivity) for a negative count, a non-finite or
// reversed range, heights or diameters not > 0, a reflectivity outside 0..1; and "<where>.area"
// if a tree would stand off the terrain grid.
[[nodiscard]] std::vector<Cylinder> generate_forest(const ForestSpec& spec, std::uint64_t seed,
                                                    const Terrain& terrain,
                                                    std::string_view where = "scene.forest");

}  // namespace owsim
