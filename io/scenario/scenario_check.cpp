#include "io/scenario/scenario_check.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "geometry/error.hpp"
#include "geometry/forest.hpp"
#include "geometry/number_text.hpp"
#include "geometry/span.hpp"
#include "io/files/utf8_text.hpp"
#include "io/scenario/value_ranges.hpp"
#include "sensor/savitzky_golay.hpp"
#include "sensor/scan_params_check.hpp"
#include "sensor/weather.hpp"

namespace owsim {
namespace {

std::string indexed(std::string_view list, std::size_t index) {
  return std::string(list) + "[" + std::to_string(index) + "]";
}

void require_finite(double value, const std::string& key) {
  if (!std::isfinite(value))
    throw input_error(key, "must be a finite number, got " + number_text(value));
}

void require_positive(double value, const std::string& key) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw input_error(key, "must be > 0, got " + number_text(value));
  }
}

void require_fraction(double value, const std::string& key) {
  if (!(value >= 0.0 && value <= 1.0)) {
    throw input_error(key, "must be between 0 and 1, got " + number_text(value));
  }
}

// The physical range of `key` (io/scenario/value_ranges.hpp), as the loader checks it.
void require_in_range(double value, const std::string& key) {
  if (const std::string problem = out_of_range_problem(key, value); !problem.empty()) {
    throw input_error(key, problem);
  }
}

void require_position_in_range(const Eigen::Vector3d& enu_m, const std::string& key) {
  require_in_range(enu_m.x(), key + ".e");
  require_in_range(enu_m.y(), key + ".n");
  require_in_range(enu_m.z(), key + ".u");
}

void check_ranges(const Scenario& scenario) {
  require_in_range(scenario.origin.lat_deg, "origin.lat");
  require_in_range(scenario.origin.lon_deg, "origin.lon");
  require_in_range(scenario.origin.h_m, "origin.h");
  const ScanParams& scan = scenario.scan;
  require_in_range(scan.prf_hz, "sensor.prf_hz");
  require_in_range(scan.fibers_per_line, "sensor.fibers_per_line");
  require_in_range(scan.lines_per_frame, "sensor.lines_per_frame");
  require_in_range(scan.sweep_deg, "sensor.sweep_deg");
  require_in_range(scan.sawtooth_deg, "sensor.sawtooth_deg");
  require_in_range(scan.frame_jitter_deg, "sensor.frame_jitter_deg");
  require_in_range(scan.look_into_turn_s, "sensor.look_into_turn_s");
  require_in_range(scan.look_into_turn_limit_deg, "sensor.look_into_turn_limit_deg");
  require_in_range(scan.hellas_mirror_angle_factor_deg, "sensor.hellas_mirror_angle_factor_deg");
  for (std::size_t i = 0; i < scan.alpha_table_deg.size(); ++i) {
    require_in_range(scan.alpha_table_deg[i], indexed("sensor.alpha_table_deg", i));
  }
  require_in_range(scenario.receiver.threshold, "sensor.threshold");
  require_in_range(scenario.receiver.range_noise_sigma_m, "sensor.range_noise_sigma_m");
  require_in_range(scenario.receiver.min_return_separation_m, "sensor.min_return_separation_m");
  const ReceiverNoiseParams& noise = scenario.receiver.noise;
  require_in_range(noise.noise_at_1km, "sensor.receiver.noise_at_1km");
  require_in_range(noise.pulse_width_ns, "sensor.receiver.pulse_width_ns");
  require_in_range(noise.sun_noise, "sensor.receiver.sun_noise");
  require_in_range(noise.sky_noise, "sensor.receiver.sky_noise");
  if (scenario.receiver.sun.given) {
    require_in_range(scenario.receiver.sun.elevation_deg, "sun.elevation_deg");
  }
  require_in_range(scenario.mount.roll_deg, "sensor.mount.roll_deg");
  require_in_range(scenario.mount.pitch_deg, "sensor.mount.pitch_deg");
  require_in_range(scenario.mount.yaw_deg, "sensor.mount.yaw_deg");
  for (int axis = 0; axis < 3; ++axis) {
    require_in_range(scenario.mount.lever_arm_m[axis], indexed("sensor.mount.lever_arm_m", axis));
  }
  const TrajectorySpec& trajectory = scenario.trajectory;
  if (trajectory.source == TrajectorySpec::Source::waypoints) {
    require_in_range(trajectory.speed_mps, "trajectory.waypoints.speed_mps");
    require_in_range(trajectory.max_bank_deg, "trajectory.waypoints.max_bank_deg");
    for (std::size_t i = 0; i < trajectory.waypoints_enu_m.size(); ++i) {
      require_position_in_range(trajectory.waypoints_enu_m[i],
                                indexed("trajectory.waypoints.points", i));
    }
  }
  require_in_range(trajectory.start_s, "trajectory.start_s");
  if (trajectory.duration_s) require_in_range(*trajectory.duration_s, "trajectory.duration_s");
  const SceneSpec& scene = scenario.scene;
  if (scene.terrain.kind == TerrainKind::flat) {
    require_in_range(scene.terrain.flat_u_m, "scene.terrain.flat_u");
  }
  require_in_range(scene.terrain.reflectivity, "scene.terrain.reflectivity");
  for (std::size_t i = 0; i < scene.spans.size(); ++i) {
    const SpanSpec& span = scene.spans[i];
    const std::string key = indexed("scene.spans", i);
    require_position_in_range({span.from_en.x(), span.from_en.y(), 0.0}, key + ".from");
    require_position_in_range({span.to_en.x(), span.to_en.y(), 0.0}, key + ".to");
    require_in_range(span.support_height_1_m, key + ".support_heights_m[0]");
    require_in_range(span.support_height_2_m, key + ".support_heights_m[1]");
    require_in_range(span.lowest_point_m, key + ".lowest_point_m");
    require_in_range(1000.0 * span.conductor_diameter_m, key + ".conductor.diameter_mm");
    require_in_range(span.conductor_reflectivity, key + ".conductor.reflectivity");
    require_in_range(span.pole_diameter_m, key + ".supports.diameter_m");
    require_in_range(span.pole_reflectivity, key + ".supports.reflectivity");
    for (std::size_t k = 0; k < span.offsets.size(); ++k) {
      require_in_range(span.offsets[k].lateral_m, indexed(key + ".layout", k) + "[0]");
      require_in_range(span.offsets[k].vertical_m, indexed(key + ".layout", k) + "[1]");
    }
  }
  for (const auto& [list, cylinders] :
       {std::pair{"scene.poles", &scene.poles}, std::pair{"scene.trees", &scene.trees}}) {
    for (std::size_t i = 0; i < cylinders->size(); ++i) {
      const Cylinder& cylinder = (*cylinders)[i];
      const std::string key = indexed(list, i);
      require_position_in_range(cylinder.base_enu_m, key + ".at");
      require_in_range(cylinder.height_m, key + ".height_m");
      require_in_range(2.0 * cylinder.radius_m, key + ".diameter_m");
      require_in_range(cylinder.reflectivity, key + ".reflectivity");
    }
  }
  if (scene.forest) require_in_range(scene.forest->count, "scene.forest.count");
}

void check_name(const std::string& name) {
  if (invalid_utf8_offset(name)) throw input_error("name", "not UTF-8 text");
  if (name.empty() || name == "." || name == ".." ||
      name.find_first_of("/\\") != std::string::npos) {
    throw input_error("name",
                      "must be a non-empty name without '/' or '\\' (it names the output folder), "
                      "got '" +
                          name + "'");
  }
}

// Object ids: non-empty, without '/', each used once.
class IdCheck {
 public:
  void add(const std::string& id, const std::string& key) {
    if (id.empty()) throw input_error(key + ".id", object_id_problem(id));
    if (invalid_utf8_offset(id)) throw input_error(key + ".id", "not UTF-8 text");
    if (const std::string problem = object_id_problem(id); !problem.empty()) {
      throw input_error(key + ".id", problem);
    }
    const auto [found, inserted] = first_.emplace(id, key);
    if (!inserted) {
      throw input_error(key + ".id",
                        "duplicate id '" + id + "' (first used at " + found->second + ")");
    }
  }

 private:
  std::map<std::string, std::string> first_;
};

void check_mount(const Mount& mount) {
  require_finite(mount.roll_deg, "sensor.mount.roll_deg");
  require_finite(mount.pitch_deg, "sensor.mount.pitch_deg");
  require_finite(mount.yaw_deg, "sensor.mount.yaw_deg");
  if (!mount.lever_arm_m.allFinite()) {
    throw input_error("sensor.mount.lever_arm_m", "must be three finite numbers");
  }
}

void check_trajectory(const TrajectorySpec& trajectory) {
  if (trajectory.source == TrajectorySpec::Source::waypoints) {
    require_positive(trajectory.speed_mps, "trajectory.waypoints.speed_mps");
    const auto& points = trajectory.waypoints_enu_m;
    if (points.size() < 2) {
      throw input_error("trajectory.waypoints.points",
                        "a route needs at least 2 waypoints, got " + std::to_string(points.size()));
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::string key = indexed("trajectory.waypoints.points", i);
      if (!points[i].allFinite()) throw input_error(key, "must be three finite numbers");
      if (i > 0 && points[i] == points[i - 1])
        throw input_error(key, "repeats the previous waypoint");
    }
    if (!(trajectory.max_bank_deg > 0.0 && trajectory.max_bank_deg < 90.0)) {
      throw input_error("trajectory.waypoints.max_bank_deg",
                        "must be in (0, 90) degrees, got " + number_text(trajectory.max_bank_deg));
    }
  } else {
    if (trajectory.file.empty())
      throw input_error("trajectory.file", "expected a file name, got ''");
    if (trajectory.format != "hellsim" && trajectory.format != "csv" &&
        trajectory.format != "sbet" && trajectory.format != "ardupilot") {
      throw input_error("trajectory.format",
                        "expected one of hellsim, csv, sbet, ardupilot, got '" + trajectory.format + "'");
    }
    require_positive(trajectory.tick_s, "trajectory.tick_s");
    if (!(std::abs(trajectory.magnetic_variation_deg) <= 180.0)) {
      throw input_error(
          "trajectory.magnetic_variation_deg",
          "must be in [-180, 180] degrees, got " + number_text(trajectory.magnetic_variation_deg));
    }
    validate_smoothing({trajectory.smoothing_window, trajectory.smoothing_degree},
                       "trajectory.smoothing");
  }
  if (!(trajectory.start_s >= 0.0 && std::isfinite(trajectory.start_s))) {
    throw input_error("trajectory.start_s", "must be ≥ 0, got " + number_text(trajectory.start_s));
  }
  if (trajectory.duration_s) require_positive(*trajectory.duration_s, "trajectory.duration_s");
}

void check_cylinders(const std::vector<Cylinder>& cylinders, std::string_view list, IdCheck& ids) {
  for (std::size_t i = 0; i < cylinders.size(); ++i) {
    const Cylinder& cylinder = cylinders[i];
    const std::string key = indexed(list, i);
    ids.add(cylinder.id, key);
    if (!cylinder.base_enu_m.allFinite()) throw input_error(key + ".at", "must be finite");
    require_positive(cylinder.height_m, key + ".height_m");
    require_positive(2.0 * cylinder.radius_m, key + ".diameter_m");
    require_fraction(cylinder.reflectivity, key + ".reflectivity");
  }
}

void check_meshes(const std::vector<MeshObject>& meshes, IdCheck& ids) {
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshObject& object = meshes[i];
    const std::string key = indexed("scene.meshes", i);
    ids.add(object.id, key);
    if (object.surface != SurfaceClass::building && object.surface != SurfaceClass::pole &&
        object.surface != SurfaceClass::tree) {
      throw input_error(key + ".class", "must be building, pole or tree, got " +
                                            std::string(to_string(object.surface)));
    }
    require_fraction(object.reflectivity, key + ".reflectivity");
    const TriangleMesh& mesh = object.mesh;
    if (mesh.triangles.empty()) throw input_error(key, "the mesh has no triangles");
    for (const auto& vertex : mesh.vertices) {
      if (!vertex.allFinite()) throw input_error(key, "a vertex is not finite");
    }
    for (const auto& triangle : mesh.triangles) {
      for (const std::uint32_t corner : triangle) {
        if (corner >= mesh.vertices.size()) {
          throw input_error(key, "a triangle names vertex " + std::to_string(corner) + " of " +
                                     std::to_string(mesh.vertices.size()));
        }
      }
    }
  }
}

void check_fog(const SceneSpec& scene, IdCheck& ids) {
  require_in_range(scene.fog_backscatter_ratio_sr, "weather.backscatter_ratio_sr");
  if (scene.fog.size() > kMaxFogVolumes) {
    throw input_error("weather.fog", "at most " + std::to_string(kMaxFogVolumes) +
                                         " volumes, got " + std::to_string(scene.fog.size()));
  }
  for (std::size_t i = 0; i < scene.fog.size(); ++i) {
    const FogVolume& volume = scene.fog[i];
    const std::string key = indexed("weather.fog", i);
    ids.add(volume.id, key);
    require_in_range(volume.visibility_m, key + ".visibility_m");
    if (volume.shape == FogShape::layer &&
        !(std::isfinite(volume.base_m) && std::isfinite(volume.top_m) &&
          volume.top_m > volume.base_m)) {
      throw input_error(key + ".layer", "the top must lie above the base, got base " +
                                            number_text(volume.base_m) + " m, top " +
                                            number_text(volume.top_m) + " m");
    }
    if (volume.shape == FogShape::box &&
        !(volume.box.min().allFinite() && volume.box.max().allFinite() &&
          (volume.box.max() - volume.box.min()).minCoeff() > 0.0)) {
      throw input_error(key + ".box", "needs finite sides with min < max on every axis");
    }
  }
}

void check_scene(const Scenario& scenario) {
  const SceneSpec& scene = scenario.scene;
  require_fraction(scene.terrain.reflectivity, "scene.terrain.reflectivity");
  if (scene.terrain.kind == TerrainKind::flat)
    require_finite(scene.terrain.flat_u_m, "scene.terrain.flat_u");
  if (scene.terrain.kind == TerrainKind::grid) scene.terrain.grid.validate("scene.terrain.grid");
  if (scene.terrain.kind == TerrainKind::dem) {
    if (!scene.terrain.dem) throw Error("scene.terrain.dem: no DEM posts were loaded");
    scene.terrain.dem->validate("scene.terrain.dem");
  }
  IdCheck ids;
  for (std::size_t i = 0; i < scene.spans.size(); ++i) {
    const std::string key = indexed("scene.spans", i);
    ids.add(scene.spans[i].id, key);
    (void)build_span(scene.spans[i], scene.terrain, key);
  }
  check_cylinders(scene.poles, "scene.poles", ids);
  check_cylinders(scene.trees, "scene.trees", ids);
  check_meshes(scene.meshes, ids);
  check_fog(scene, ids);
  if (scene.forest)
    (void)generate_forest(*scene.forest, scenario.seed, scene.terrain, "scene.forest");
}

}  // namespace

std::string object_id_problem(const std::string& id) {
  if (id.empty()) return "an object needs a non-empty id";
  if (id.find('/') != std::string::npos) {
    return "'" + id + "': '/' is reserved for the ids owsim makes (\"<span>/<n>\")";
  }
  if (id == kTerrainId) return "'terrain' is the ground's id (points.csv's object column)";
  return "";
}

void validate_scenario(const Scenario& scenario) {
  check_name(scenario.name);
  check_ranges(scenario);
  validate_geodetic(scenario.origin, "origin");
  validate(scenario.scan);
  validate(scenario.receiver);
  check_mount(scenario.mount);
  check_trajectory(scenario.trajectory);
  check_scene(scenario);
  const std::vector<std::string> detector = detector_param_problems(scenario.detector);
  if (!detector.empty()) throw Error("detector." + detector.front());
}

}  // namespace owsim
