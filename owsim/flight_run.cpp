#include "owsim/flight_run.hpp"

#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>
#include <vector>

#include "geometry/error.hpp"
#include "io/detections/recording_detections.hpp"
#include "io/run/run_checkpoint.hpp"
#include "owsim/version.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

nlohmann::json run_fingerprint(const FlightSetup& setup, const SimulationOptions& simulation,
                               const std::string& source_hash, const RunOptions& options) {
  nlohmann::json run = {
      {"owsim_version", version_string}, {"scenario_file", source_hash},
      {"seed", setup.scenario.seed},     {"no_noise", simulation.no_noise},
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
  if (setup.scenario.scene.terrain.kind == TerrainKind::dem) {
    const PostLattice& dem = *setup.scenario.scene.terrain.dem;
    ContentHash terrain;
    const double shape[] = {static_cast<double>(dem.ncols), static_cast<double>(dem.nrows)};
    terrain.add(shape, sizeof shape);
    terrain.add(dem.posts.data(), dem.posts.size() * sizeof(Eigen::Vector3d));
    terrain.add(dem.valid.data(), dem.valid.size());
    run["terrain_dem"] = terrain.hex();
  }
  if (!setup.scene.meshes.empty()) {
    ContentHash meshes;
    for (const MeshObject& mesh : setup.scene.meshes) {
      meshes.add(mesh.mesh.vertices.data(), mesh.mesh.vertices.size() * sizeof(Eigen::Vector3d));
      meshes.add(mesh.mesh.triangles.data(),
                 mesh.mesh.triangles.size() * sizeof(mesh.mesh.triangles.front()));
    }
    run["scene_meshes"] = meshes.hex();
  }
  return run;
}

std::optional<RunCheckpoint> checkpoint_to_resume(const FlightOutputOptions& output_options,
                                                  std::int64_t frames, const RunOptions& options) {
  const std::filesystem::path path = run_checkpoint_path(output_options.directory);
  std::optional<RunCheckpoint> checkpoint = read_run_checkpoint(path);
  if (!checkpoint) {
    const std::filesystem::path json_path = output_options.directory / kJsonRunCheckpointFileName;
    if (std::filesystem::exists(json_path)) {
      throw input_error(json_path.string(),
                        "a JSON checkpoint of an earlier owsim, which this one cannot resume; "
                        "run without --resume to start over");
    }
    if (options.notice) {
      options.notice("no checkpoint " + path.string() + ": starting from frame 0");
    }
    return std::nullopt;
  }
  require_same_run(path, checkpoint->run, output_options.checkpoint_run);
  if (checkpoint->frames_done > frames) {
    throw input_error(path.string(),
                      "damaged checkpoint: " + std::to_string(checkpoint->frames_done) +
                          " frames done of " + std::to_string(frames));
  }
  if (options.notice) {
    options.notice("resuming " + output_options.directory.string() + " at frame " +
                   std::to_string(checkpoint->frames_done) + " of " + std::to_string(frames));
  }
  return checkpoint;
}

FlightOutputOptions flight_output_options(const FlightSetup& setup,
                                          const std::optional<std::filesystem::path>& out,
                                          const std::set<OutputKind>& outputs) {
  FlightOutputOptions output_options;
  output_options.directory = out ? *out : std::filesystem::path("out") / setup.scenario.name;
  output_options.outputs = outputs;
  output_options.sensor_mount = setup.scenario.mount;
  if (outputs.contains(OutputKind::truth)) output_options.truth = &setup.truth_model();
  output_options.map_region = setup.flown.merged(scene_extent(setup.scene));
  output_options.map_region.min().array() -= 50.0;  // a margin around what was flown and built
  output_options.map_region.max().array() += 50.0;
  return output_options;
}

FlightOutputOptions run_output_options(const FlightSetup& setup, const nlohmann::json& fingerprint,
                                       const RunOptions& options) {
  if (fingerprint.is_null() && options.resume) {
    throw Error(setup.scenario.name +
                ": resume: a scenario built in code keeps no checkpoint; open it from a file or "
                "from YAML text to resume its runs");
  }
  if (options.resume && options.outputs.contains(OutputKind::mcap)) {
    throw input_error("--resume",
                      "flight.mcap (output mcap) cannot be continued from a "
                      "checkpoint; run without --resume, or without mcap");
  }
  FlightOutputOptions output_options = flight_output_options(setup, options.out, options.outputs);
  output_options.checkpoint_run = fingerprint;
  return output_options;
}

void encode_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                   const FlightRange& range, int threads, const FrameEncoder& encoder,
                   const std::function<void(const FrameView&, const FrameEncoding&)>& sink,
                   FrameRecordScope records, FlightDetections* detections) {
  if (detections != nullptr && !encoder.wants(OutputKind::d64)) {
    throw Error("engine: the detector reads the words; the encoder does not encode them");
  }
  if (records == FrameRecordScope::block && encoder.reads_frame_records()) {
    throw Error("engine: the encoder reads whole frames; their records cannot be left in blocks");
  }
  // Each frame is itself simulated in parallel, so one frame per thread keeps every core busy;
  // more frames in flight only add their buffers (4.1 MB each on the corridor: pulses, rays and
  // returns) to what competes with the scene for the cache. `owsim bench` on the corridor with 2
  // threads: 19.9-20.0 M pulses/s with 2 frames in flight, 19.2-19.4 M with 3, 19.0-19.4 M with
  // 1; single-threaded, 10.1-10.2 M with 1 frame in flight and 9.8 M with 2.
  // Never more than the frames to run, nor than the cores that can work on them at once: a
  // thread count above the cores (`--threads 4096` on 2 cores) adds buffers, not speed.
  const auto cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int frames_in_flight = static_cast<int>(
      std::max<std::int64_t>(1, std::min<std::int64_t>({threads, cores, range.frame_count})));
  // One encoding per buffer of the pipeline: a frame is encoded where it is simulated, in the
  // parallel stage, and the in-order sink only appends its bytes. The words and the summary's
  // tally are encoded block by block while the simulation has the block's pulses and returns in
  // cache; the rest (points, HELLAS header) once the frame is whole.
  std::vector<FrameEncoding> encodings(static_cast<std::size_t>(frames_in_flight));
  for (FrameEncoding& encoding : encodings) encoder.size_encoding(encoding);
  // The detector's frames, decoded from the words where the frames were simulated.
  std::vector<PreparedDetectorFrame> prepared(detections ? encodings.size() : 0);
  run_flight(
      simulator, setup.trajectory, range, frames_in_flight,
      [&](const FrameResult& frame, const FrameView& block, int begin) {
        encoder.encode_pulses(block, begin, encodings[static_cast<std::size_t>(frame.buffer)]);
      },
      [&](const FrameResult& frame) {
        FrameEncoding& encoding = encodings[static_cast<std::size_t>(frame.buffer)];
        encoder.finish_encoding(
            frame.view(),
            setup.trajectory.pose_at(pulse_time_s(setup.scenario.scan, frame.frame, 0)), encoding);
        if (detections != nullptr && !encoding.error) {
          try {
            detections->prepare(frame.frame, encoding.milows_words, encoding.hellas_words,
                                frame.frame == 0 ? std::optional(encoding.hellas_header_word)
                                                 : std::nullopt,
                                prepared[static_cast<std::size_t>(frame.buffer)]);
          } catch (...) {
            encoding.error = std::current_exception();
          }
        }
      },
      [&](const FrameResult& frame) {
        const FrameEncoding& encoding = encodings[static_cast<std::size_t>(frame.buffer)];
        if (detections != nullptr && !encoding.error) {
          detections->add(prepared[static_cast<std::size_t>(frame.buffer)]);
        }
        sink(frame.view(), encoding);
      },
      records);
}

void simulate_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                     const FlightRange& range, int threads, FlightOutputs& outputs,
                     const std::function<void(std::int64_t)>& frame_done,
                     FlightDetections* detections) {
  std::int64_t done = 0;
  encode_frames(
      simulator, setup, range, threads, outputs.encoder(),
      [&](const FrameView& frame, const FrameEncoding& encoding) {
        outputs.add_frame(frame, encoding);
        ++done;
        if (frame_done) frame_done(done);
      },
      outputs.reads_frame_records() ? FrameRecordScope::frame : FrameRecordScope::block,
      detections);
}

RunReport run_flight_outputs(const FlightSetup& setup, const SimulationOptions& simulation,
                             const std::string& source_hash, const FlownScenario& flown,
                             const RunOptions& options, int threads, double build_s) {
  const auto opening = Clock::now();
  const Scenario& scenario = setup.scenario;
  const std::int64_t frames = setup.frames;
  FlightOutputOptions output_options = run_output_options(
      setup,
      source_hash.empty() ? nlohmann::json()
                          : run_fingerprint(setup, simulation, source_hash, options),
      options);
  output_options.scenario = flown;
  std::optional<RunCheckpoint> checkpoint;
  if (options.resume) checkpoint = checkpoint_to_resume(output_options, frames, options);
  FlightOutputs outputs(output_options, setup.scene, scenario.scan, setup.local_frame,
                        checkpoint ? &*checkpoint : nullptr);
  const std::int64_t first = outputs.frames_done();
  std::optional<FlightDetections> detections;
  if (options.outputs.contains(OutputKind::detections)) {
    detections.emplace(scenario, setup.trajectory, output_options.directory / "detections.csv");
    // A resumed run's detector first sees again the frames its checkpoint holds.
    if (first > 0) detections->replay(outputs.placed_files().words.partial_path, first);
  }

  const auto start = Clock::now();
  simulate_frames(
      setup.simulator, setup, FlightRange{first, frames - first}, threads, outputs,
      [&](std::int64_t done) {
        if (!options.progress) return;
        options.progress(RunProgress{first + done, frames, first,
                                     std::chrono::duration<double>(Clock::now() - start).count()});
      },
      detections ? &*detections : nullptr);
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  RunReport report = run_report(setup, output_options.directory, first, wall_s, threads, 1);
  report.setup_s = build_s + std::chrono::duration<double>(start - opening).count();
  outputs.finish(run_facts(scenario, report));
  if (detections) detections->finish();
  return report;
}

void write_run_detections(const FlightSetup& setup, const FlownScenario& flown,
                          const std::filesystem::path& directory) {
  if (!flown.yaml.empty()) {
    detect_run_folder(directory, directory / "detections.csv");
    return;
  }
  detect_word_file(setup.scenario, directory / word_file_name(setup.scenario.scan),
                   directory / "detections.csv");
}

RunReport run_report(const FlightSetup& setup, const std::filesystem::path& directory,
                     std::int64_t first_frame, double wall_s, int threads, int processes) {
  const auto pulses_per_frame = static_cast<std::uint64_t>(setup.scenario.scan.pulses_per_frame());
  RunReport report;
  report.directory = directory;
  report.frames = setup.frames;
  report.first_frame = first_frame;
  report.pulses = static_cast<std::uint64_t>(setup.frames) * pulses_per_frame;
  report.wall_s = wall_s;
  const auto simulated = static_cast<double>(
      static_cast<std::uint64_t>(setup.frames - first_frame) * pulses_per_frame);
  report.pulses_per_s = wall_s > 0 ? simulated / wall_s : 0.0;
  report.realtime_factor = report.pulses_per_s / setup.scenario.scan.prf_hz;
  report.threads = threads;
  report.processes = processes;
  return report;
}

nlohmann::json run_facts(const Scenario& scenario, const RunReport& report) {
  return {{"scenario", scenario.name},
          {"seed", scenario.seed},
          {"setup_s", report.setup_s},
          {"wall_s", report.wall_s},
          {"pulses_per_s", report.pulses_per_s},
          {"realtime_factor", report.realtime_factor},
          {"threads", report.threads},
          {"processes", report.processes},
          {"version", version_string}};
}

}  // namespace owsim
