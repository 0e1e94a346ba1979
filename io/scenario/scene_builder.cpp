#include "io/scenario/scene_builder.hpp"

#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "geometry/forest.hpp"
#include "geometry/span.hpp"

namespace owsim {
namespace {

// Puts the scenario's file in front of a message that names the key ("scene.spans[0]…: …").
[[noreturn]] void rethrow_in_file(const Scenario& scenario, const Error& error) {
  if (scenario.path.empty()) throw error;
  throw input_error(scenario.path.string(), error.what());
}

}  // namespace

Scene build_scene(const Scenario& scenario) {
  const SceneSpec& spec = scenario.scene;
  Scene scene;
  scene.terrain = spec.terrain;
  try {
    for (std::size_t i = 0; i < spec.spans.size(); ++i) {
      SpanObjects span =
          build_span(spec.spans[i], spec.terrain, "scene.spans[" + std::to_string(i) + "]");
      for (Conductor& conductor : span.conductors) scene.conductors.push_back(std::move(conductor));
      for (Cylinder& pole : span.poles) scene.cylinders.push_back(std::move(pole));
    }
    for (const Cylinder& pole : spec.poles) {
      scene.cylinders.push_back(pole);
      scene.cylinders.back().surface = SurfaceClass::pole;
    }
    for (const Cylinder& tree : spec.trees) {
      scene.cylinders.push_back(tree);
      scene.cylinders.back().surface = SurfaceClass::tree;
    }
    if (spec.forest) {
      std::vector<Cylinder> forest = generate_forest(*spec.forest, scenario.seed, spec.terrain);
      for (Cylinder& tree : forest) scene.cylinders.push_back(std::move(tree));
    }
    scene.meshes = spec.meshes;
    scene.fog = spec.fog;
    scene.fog_backscatter_ratio_sr = spec.fog_backscatter_ratio_sr;
  } catch (const Error& error) {
    rethrow_in_file(scenario, error);
  }
  return scene;
}

}  // namespace owsim
