#include "cli/flight_run.hpp"

#include <fmt/core.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/progress_line.hpp"
#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/flight_pipeline.hpp"
#include "engine/frame_simulator.hpp"
#include "geometry/error.hpp"
#include "io/run_checkpoint.hpp"
#include "io/scenario_loader.hpp"
#include "io/scene_builder.hpp"
#include "io/trajectory_loader.hpp"
#include "owsim/version.hpp"
#include "sensor/range_counter.hpp"

namespace owsim::cli {
namespace {

using Clock = std::chrono::steady_clock;

// How many whole frames the run simulates: --frames, else --duration, else the scenario's
// duration_s, else as many as the trajectory holds; never past the trajectory's end.
std::int64_t frame_count(const RunOptions& options, const Scenario& scenario,
                         const Trajectory& trajectory) {
  const ScanParams& scan = scenario.scan;
  const double frame_s = scan.frame_duration_s();
  if (scan.start_s < trajectory.start_s()) {
    throw input_error(scenario.path.string() + ": trajectory.start_s",
                      "the sensor starts at " + std::to_string(scan.start_s) +
                          " s, before the trajectory begins (" +
                          std::to_string(trajectory.start_s()) + " s)");
  }
  const auto available =
      static_cast<std::int64_t>(std::floor((trajectory.end_s() - scan.start_s) / frame_s));
  std::int64_t frames = available;
  if (options.frames) {
    frames = *options.frames;
  } else if (const auto duration =
                 options.duration_s ? options.duration_s : scenario.trajectory.duration_s) {
    frames = static_cast<std::int64_t>(std::floor(*duration / frame_s + 1e-9));
  }
  if (frames < 1) {
    throw input_error(
        options.duration_s ? "--duration" : scenario.path.string() + ": trajectory.duration_s",
        "the run is shorter than one frame (" + std::to_string(frame_s) + " s)");
  }
  if (frames > available) {
    throw Error(scenario.path.string() + ": the trajectory ends at " +
                std::to_string(trajectory.end_s()) + " s: only " + std::to_string(available) +
                " frames fit, " + std::to_string(frames) + " were asked for");
  }
  return frames;
}

// The east/north extent of the trajectory over the run (sampled at every frame start).
Eigen::AlignedBox2d flight_extent(const Trajectory& trajectory, const ScanParams& scan,
                                  std::int64_t frames) {
  Eigen::AlignedBox2d box;
  for (std::int64_t f = 0; f <= frames; ++f) {
    const Pose pose = trajectory.pose_at(
        pulse_time_s(scan, std::min(f, frames - 1), f == frames ? scan.pulses_per_frame() - 1 : 0));
    box.extend(pose.position_enu_m.head<2>());
  }
  return box;
}

Eigen::AlignedBox2d scene_extent(const Scene& scene) {
  Eigen::AlignedBox2d box;
  for (const Conductor& conductor : scene.conductors) {
    for (const auto& point : conductor.points_enu_m) box.extend(point.head<2>());
  }
  for (const Cylinder& cylinder : scene.cylinders) box.extend(cylinder.base_enu_m.head<2>());
  return box;
}

// The scenario file with --seed and --no-noise applied.
Scenario scenario_of_run(const RunOptions& options) {
  Scenario scenario = load_scenario(options.scenario);
  if (options.seed) scenario.seed = *options.seed;
  if (options.no_noise) scenario.receiver.range_noise_sigma_m = 0.0;
  return scenario;
}

// What the sensor can reach over the run: the flown extent widened by the timeout range.
Eigen::AlignedBox2d reach_of(const Eigen::AlignedBox2d& flown, double max_range_m) {
  Eigen::AlignedBox2d reach = flown;
  reach.min().array() -= max_range_m;
  reach.max().array() += max_range_m;
  return reach;
}

// "d64,points,…": the outputs in a fixed order.
std::string output_list(const std::set<OutputKind>& outputs) {
  static constexpr std::pair<OutputKind, const char*> kNames[] = {
      {OutputKind::d64, "d64"},
      {OutputKind::points, "points"},
      {OutputKind::trajectory, "trajectory"},
      {OutputKind::summary, "summary"},
      {OutputKind::quicklook, "quicklook"}};
  std::string list;
  for (const auto& [kind, name] : kNames) {
    if (!outputs.contains(kind)) continue;
    if (!list.empty()) list += ',';
    list += name;
  }
  return list;
}

// What makes a run's output bytes (io/run_checkpoint.hpp `run`): owsim's version, the contents of
// the scenario file and of the files it reads, and the options that change bytes. Not the thread
// count, which changes none.
nlohmann::json run_fingerprint(const FlightSetup& setup, const RunOptions& options) {
  ContentHash scenario_file;
  scenario_file.add_file(options.scenario);
  nlohmann::json run = {
      {"owsim_version", version_string}, {"scenario_file", scenario_file.hex()},
      {"seed", setup.scenario.seed},     {"no_noise", options.no_noise},
      {"frames", setup.frames},          {"outputs", output_list(options.outputs)}};
  if (setup.scenario.trajectory.source == TrajectorySpec::Source::file) {
    ContentHash trajectory_file;
    trajectory_file.add_file(setup.scenario.trajectory.file);
    run["trajectory_file"] = trajectory_file.hex();
  }
  if (setup.scenario.scene.terrain.kind == TerrainKind::grid) {
    const HeightGrid& grid = setup.scenario.scene.terrain.grid;
    ContentHash terrain;
    const double shape[] = {static_cast<double>(grid.ncols),
                            static_cast<double>(grid.nrows),
                            grid.x_west_m,
                            grid.y_south_m,
                            grid.cellsize_m,
                            grid.nodata.value_or(0.0)};
    terrain.add(shape, sizeof shape);
    terrain.add(grid.heights.data(), grid.heights.size() * sizeof(double));
    run["terrain_grid"] = terrain.hex();
  }
  return run;
}

// The checkpoint --resume continues from, compared with this run; std::nullopt (and a note) if
// the folder has none.
std::optional<RunCheckpoint> checkpoint_to_resume(const FlightOutputOptions& output_options,
                                                  std::int64_t frames, bool verbose) {
  const std::filesystem::path path = run_checkpoint_path(output_options.directory);
  std::optional<RunCheckpoint> checkpoint = read_run_checkpoint(path);
  if (!checkpoint) {
    fmt::print(stderr, "owsim run --resume: no checkpoint {}: starting from frame 0\n",
               path.string());
    return std::nullopt;
  }
  require_same_run(path, checkpoint->run, output_options.checkpoint_run);
  if (checkpoint->frames_done > frames) {
    throw input_error(path.string(),
                      "damaged checkpoint: " + std::to_string(checkpoint->frames_done) +
                          " frames done of " + std::to_string(frames));
  }
  if (verbose) {
    fmt::print(stderr, "resuming {} at frame {} of {}\n", output_options.directory.string(),
               checkpoint->frames_done, frames);
  }
  return checkpoint;
}

}  // namespace

FlightSetup::FlightSetup(const RunOptions& options)
    : scenario(scenario_of_run(options)),
      local_frame(scenario.origin),
      scene(build_scene(scenario)),
      trajectory(load_trajectory(scenario, local_frame)),
      frames(frame_count(options, scenario, trajectory)),
      flown(flight_extent(trajectory, scenario.scan, frames)),
      embree_scene(device, scene, scenario.receiver,
                   reach_of(flown, timeout_range_m(scenario.receiver.counter)),
                   timeout_range_m(scenario.receiver.counter)),
      simulator(
          FrameSimulatorParams{scenario.scan, scenario.receiver, scenario.mount, scenario.seed},
          embree_scene, options.trace_api) {}

FlightOutputOptions flight_output_options(const FlightSetup& setup, const RunOptions& options) {
  FlightOutputOptions output_options;
  output_options.directory =
      options.out ? *options.out : std::filesystem::path("out") / setup.scenario.name;
  output_options.outputs = options.outputs;
  output_options.map_region = setup.flown.merged(scene_extent(setup.scene));
  output_options.map_region.min().array() -= 50.0;  // a margin around what was flown and built
  output_options.map_region.max().array() += 50.0;
  return output_options;
}

void simulate_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                     const FlightRange& range, int threads, FlightOutputs& outputs,
                     const std::function<void(std::int64_t)>& frame_done) {
  // Each frame is itself simulated in parallel, so one frame per thread keeps every core busy;
  // more frames in flight only add their buffers (4.1 MB each on the corridor: pulses, rays and
  // returns) to what competes with the scene for the cache. `owsim bench` on the corridor with 2
  // threads: 19.9-20.0 M pulses/s with 2 frames in flight, 19.2-19.4 M with 3, 19.0-19.4 M with
  // 1; single-threaded, 10.1-10.2 M with 1 frame in flight and 9.8 M with 2.
  const int frames_in_flight = std::max(1, threads);
  // One encoding per buffer of the pipeline: a frame is encoded where it is simulated, in the
  // parallel stage, and the in-order sink only appends its bytes. The words and the summary's
  // tally are encoded block by block while the simulation has the block's pulses and returns in
  // cache; the rest (points, HELLAS header) once the frame is whole.
  std::vector<FrameEncoding> encodings(static_cast<std::size_t>(frames_in_flight));
  for (FrameEncoding& encoding : encodings) outputs.size_encoding(encoding);
  std::int64_t done = 0;
  run_flight(
      simulator, setup.trajectory, range, frames_in_flight,
      [&](const FrameResult& frame, int begin, int end) {
        outputs.encode_pulses(frame.view(), begin, end,
                              encodings[static_cast<std::size_t>(frame.buffer)]);
      },
      [&](const FrameResult& frame) {
        outputs.finish_encoding(frame.view(),
                                setup.trajectory.pose_at(frame.pulses.front().time_s),
                                encodings[static_cast<std::size_t>(frame.buffer)]);
      },
      [&](const FrameResult& frame) {
        outputs.add_frame(frame.view(), encodings[static_cast<std::size_t>(frame.buffer)]);
        ++done;
        if (frame_done) frame_done(done);
      });
}

RunReport run_flight_scenario(const RunOptions& options) {
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));

  const FlightSetup setup(options);
  const Scenario& scenario = setup.scenario;
  const std::int64_t frames = setup.frames;
  FlightOutputOptions output_options = flight_output_options(setup, options);
  output_options.checkpoint_run = run_fingerprint(setup, options);
  std::optional<RunCheckpoint> checkpoint;
  if (options.resume) checkpoint = checkpoint_to_resume(output_options, frames, options.progress);
  FlightOutputs outputs(output_options, setup.scene, scenario.scan, setup.local_frame,
                        checkpoint ? &*checkpoint : nullptr);
  const std::int64_t first = outputs.frames_done();

  const auto pulses_per_frame = static_cast<std::uint64_t>(scenario.scan.pulses_per_frame());
  ProgressLine progress(options.progress, static_cast<std::uint64_t>(frames),
                        static_cast<std::uint64_t>(first));
  const auto start = Clock::now();
  simulate_frames(setup.simulator, setup, FlightRange{first, frames - first}, threads, outputs,
                  [&](std::int64_t done) {
                    progress.frame_done(static_cast<std::uint64_t>(first + done),
                                        static_cast<std::uint64_t>(done) * pulses_per_frame);
                  });
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();

  RunReport report;
  report.directory = output_options.directory;
  report.frames = frames;
  report.first_frame = first;
  report.pulses = static_cast<std::uint64_t>(frames) * pulses_per_frame;
  report.wall_s = wall_s;
  const auto simulated =
      static_cast<double>(static_cast<std::uint64_t>(frames - first) * pulses_per_frame);
  report.pulses_per_s = wall_s > 0 ? simulated / wall_s : 0.0;
  report.realtime_factor = report.pulses_per_s / scenario.scan.prf_hz;
  report.threads = threads;

  outputs.finish({{"scenario", scenario.name},
                  {"seed", scenario.seed},
                  {"wall_s", report.wall_s},
                  {"pulses_per_s", report.pulses_per_s},
                  {"realtime_factor", report.realtime_factor},
                  {"threads", threads},
                  {"version", version_string}});
  return report;
}

}  // namespace owsim::cli
