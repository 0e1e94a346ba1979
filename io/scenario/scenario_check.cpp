#include "io/scenario/scenario_check.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "geometry/error.hpp"
#include "geometry/forest.hpp"
#include "geometry/span.hpp"
#include "sensor/savitzky_golay.hpp"
#include "sensor/scan_params_check.hpp"

namespace owsim {
namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

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

void check_name(const std::string& name) {
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
    if (id.empty()) throw input_error(key + ".id", "an object needs a non-empty id");
    if (id.find('/') != std::string::npos) {
      throw input_error(key + ".id",
                        "'" + id + "': '/' is reserved for the ids owsim makes (\"<span>/<n>\")");
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
        trajectory.format != "sbet") {
      throw input_error("trajectory.format",
                        "expected one of hellsim, csv, sbet, got '" + trajectory.format + "'");
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

void check_scene(const Scenario& scenario) {
  const SceneSpec& scene = scenario.scene;
  require_fraction(scene.terrain.reflectivity, "scene.terrain.reflectivity");
  if (scene.terrain.kind == TerrainKind::flat)
    require_finite(scene.terrain.flat_u_m, "scene.terrain.flat_u");
  if (scene.terrain.kind == TerrainKind::grid) scene.terrain.grid.validate("scene.terrain.grid");
  IdCheck ids;
  for (std::size_t i = 0; i < scene.spans.size(); ++i) {
    const std::string key = indexed("scene.spans", i);
    ids.add(scene.spans[i].id, key);
    (void)build_span(scene.spans[i], scene.terrain, key);
  }
  check_cylinders(scene.poles, "scene.poles", ids);
  check_cylinders(scene.trees, "scene.trees", ids);
  if (scene.forest)
    (void)generate_forest(*scene.forest, scenario.seed, scene.terrain, "scene.forest");
}

}  // namespace

void validate_scenario(const Scenario& scenario) {
  check_name(scenario.name);
  validate_geodetic(scenario.origin, "origin");
  validate(scenario.scan);
  validate(scenario.receiver);
  check_mount(scenario.mount);
  check_trajectory(scenario.trajectory);
  check_scene(scenario);
}

}  // namespace owsim
