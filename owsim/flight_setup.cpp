#include "owsim/flight_setup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "io/scenario/scene_builder.hpp"
#include "io/scenario/value_ranges.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

constexpr int kMaxThreads = 4096;
// The longest run, in frames (about 38 days of sensor time): counts stay far from overflow.
constexpr std::int64_t kMaxFrames = 10'000'000;

// Throws "<where()>: lies … m from the scenario origin; …" unless every coordinate of `enu_m` is
// within kMaxOffsetFromOriginM: the ray tracer works in floats relative to the origin. `where`
// makes its text only for the error (it is asked for every conductor vertex and frame start).
template <typename Where>
void require_near_origin(const Eigen::Vector3d& enu_m, const Where& where) {
  const double offset = enu_m.cwiseAbs().maxCoeff();
  if (offset <= kMaxOffsetFromOriginM) return;
  throw input_error(where(), "lies " + number_text(offset, 6) +
                                 " m from the scenario origin; owsim simulates within " +
                                 number_text(kMaxOffsetFromOriginM, 6) +
                                 " m of it (the ray tracer's float coordinates keep 16 mm there): "
                                 "put the origin near the flight");
}

const Scene& checked_near_origin(const Scene& scene, const std::string& scenario) {
  for (const Conductor& conductor : scene.conductors) {
    for (const auto& point : conductor.points_enu_m) {
      require_near_origin(point,
                          [&] { return scenario + ": scene object '" + conductor.id + "'"; });
    }
  }
  for (const Cylinder& cylinder : scene.cylinders) {
    require_near_origin(cylinder.base_enu_m + Eigen::Vector3d(0, 0, cylinder.height_m),
                        [&] { return scenario + ": scene object '" + cylinder.id + "'"; });
  }
  for (const MeshObject& mesh : scene.meshes) {
    for (const auto& vertex : mesh.mesh.vertices) {
      require_near_origin(vertex, [&] { return scenario + ": scene object '" + mesh.id + "'"; });
    }
  }
  return scene;
}

// Options that cannot describe a run, named as `owsim run` spells them.
void check_options(const SimulationOptions& options) {
  if (options.frames && options.duration_s) {
    throw input_error("--frames", "give --frames or --duration, not both");
  }
  if (options.frames && !(*options.frames >= 1 && *options.frames <= kMaxFrames)) {
    throw input_error("--frames", "must be in [1, " + std::to_string(kMaxFrames) + "], got " +
                                      std::to_string(*options.frames));
  }
  if (options.duration_s && !(*options.duration_s > 0 && *options.duration_s <= 86'400.0 * 38)) {
    throw input_error("--duration", "must be a positive number of seconds up to 38 days");
  }
  if (options.threads < 0 || options.threads > kMaxThreads) {
    throw input_error("--threads", "must be between 1 and " + std::to_string(kMaxThreads) +
                                       " (0: every core), got " + std::to_string(options.threads));
  }
  if (const auto& area = options.flight_area_enu_m) {
    if (area->isEmpty() || !area->min().allFinite() || !area->max().allFinite()) {
      throw input_error("flight_area_enu_m", "must be a finite, non-empty east/north box");
    }
  }
}

// The scenario with the options' seed and noise overrides (--no-noise: range noise and the
// receiver's noise off).
Scenario with_overrides(Scenario scenario, const SimulationOptions& options) {
  check_options(options);
  if (options.seed) scenario.seed = *options.seed;
  if (options.no_noise) {
    scenario.receiver.range_noise_sigma_m = 0.0;
    scenario.receiver.noise.on = false;
  }
  return scenario;
}

std::string scenario_name(const Scenario& scenario) {
  return scenario.path.empty() ? scenario.name : scenario.path.string();
}

// How many whole frames the simulation holds: options.frames, else options.duration_s, else the
// scenario's duration_s, else as many as the trajectory holds; never past the trajectory's end.
std::int64_t frame_count(const SimulationOptions& options, const Scenario& scenario,
                         const Trajectory& trajectory) {
  const ScanParams& scan = scenario.scan;
  const double frame_s = scan.frame_duration_s();
  if (scan.start_s < trajectory.start_s()) {
    throw input_error(scenario_name(scenario) + ": trajectory.start_s",
                      "the sensor starts at " + std::to_string(scan.start_s) +
                          " s, before the trajectory begins (" +
                          std::to_string(trajectory.start_s()) + " s)");
  }
  const double fit = std::floor((trajectory.end_s() - scan.start_s) / frame_s);
  if (!std::isfinite(fit)) {
    throw input_error(scenario_name(scenario) + ": trajectory",
                      "its times do not give a finite length of flight");
  }
  const auto available =
      static_cast<std::int64_t>(std::clamp(fit, 0.0, static_cast<double>(kMaxFrames)));
  std::int64_t frames = available;
  if (options.frames) {
    frames = *options.frames;
  } else if (const auto duration =
                 options.duration_s ? options.duration_s : scenario.trajectory.duration_s) {
    frames = static_cast<std::int64_t>(
        std::min(std::floor(*duration / frame_s + 1e-9), static_cast<double>(kMaxFrames) + 1));
  }
  if (frames < 1) {
    throw input_error(
        options.duration_s ? "--duration" : scenario_name(scenario) + ": trajectory.duration_s",
        "the run is shorter than one frame (" + std::to_string(frame_s) + " s)");
  }
  if (frames > available) {
    throw Error(scenario_name(scenario) + ": the trajectory ends at " +
                std::to_string(trajectory.end_s()) + " s: only " + std::to_string(available) +
                " frames fit, " + std::to_string(frames) + " were asked for");
  }
  return frames;
}

// The east/north extent of the trajectory over the run (sampled at every frame start), every
// sample near the origin (require_near_origin).
Eigen::AlignedBox2d flight_extent(const Trajectory& trajectory, const Scenario& scenario,
                                  std::int64_t frames) {
  const ScanParams& scan = scenario.scan;
  const std::string source = scenario.trajectory.source == TrajectorySpec::Source::file
                                 ? scenario.trajectory.file.string()
                                 : scenario_name(scenario) + ": trajectory.waypoints";
  Eigen::AlignedBox2d box;
  for (std::int64_t f = 0; f <= frames; ++f) {
    const double t_s =
        pulse_time_s(scan, std::min(f, frames - 1), f == frames ? scan.pulses_per_frame() - 1 : 0);
    const Pose pose = trajectory.pose_at(t_s);
    require_near_origin(pose.position_enu_m, [&] {
      return source + ": the flight at t = " + number_text(t_s, 6) + " s";
    });
    box.extend(pose.position_enu_m.head<2>());
  }
  return box;
}

Eigen::AlignedBox2d flight_area(const Eigen::AlignedBox2d& flown,
                                const SimulationOptions& options) {
  return options.flight_area_enu_m ? flown.merged(*options.flight_area_enu_m) : flown;
}

// What the sensor can reach: the area flown in, widened by the timeout range.
Eigen::AlignedBox2d reach_of(const Eigen::AlignedBox2d& area, double max_range_m) {
  Eigen::AlignedBox2d reach = area;
  reach.min().array() -= max_range_m;
  reach.max().array() += max_range_m;
  return reach;
}

}  // namespace

Eigen::AlignedBox2d scene_extent(const Scene& scene) {
  Eigen::AlignedBox2d box;
  for (const Conductor& conductor : scene.conductors) {
    for (const auto& point : conductor.points_enu_m) box.extend(point.head<2>());
  }
  for (const Cylinder& cylinder : scene.cylinders) box.extend(cylinder.base_enu_m.head<2>());
  for (const MeshObject& mesh : scene.meshes) {
    for (const auto& vertex : mesh.mesh.vertices) box.extend(vertex.head<2>());
  }
  return box;
}

FlightSetup::FlightSetup(Scenario scenario_in, const SimulationOptions& options)
    : scenario(with_overrides(std::move(scenario_in), options)),
      local_frame(scenario.origin),
      scene(build_scene(scenario)),
      trajectory(load_trajectory(scenario, local_frame)),
      frames(frame_count(options, scenario, trajectory)),
      flown(flight_extent(trajectory, scenario, frames)),
      area(flight_area(flown, options)),
      embree_scene(device, checked_near_origin(scene, scenario_name(scenario)), scenario.receiver,
                   reach_of(area, timeout_range_m(scenario.receiver.counter)),
                   timeout_range_m(scenario.receiver.counter)),
      simulator(
          FrameSimulatorParams{scenario.scan, scenario.receiver, scenario.mount, scenario.seed},
          embree_scene, options.trace_api.value_or(widest_native_packet(device))) {}

const FrameTruthModel& FlightSetup::truth_model() const {
  std::call_once(truth_built_, [&] {
    truth_ = std::make_unique<FrameTruthModel>(scene, scenario.scan, scenario.mount, trajectory);
  });
  return *truth_;
}

}  // namespace owsim
