#pragma once
// `owsim run` as a function: scenario → scene, trajectory, Embree scene → the frame pipeline →
// the outputs. The command only parses options into RunOptions and prints; the bench command and
// the end-to-end tests call the same function.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>

#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/flight_pipeline.hpp"
#include "engine/frame_simulator.hpp"
#include "engine/frame_tracer.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/flight_outputs.hpp"
#include "io/scenario.hpp"
#include "sensor/trajectory.hpp"

namespace owsim::cli {

struct RunOptions {
  std::filesystem::path scenario;
  std::optional<std::filesystem::path> out;  // default out/<scenario name>/
  std::optional<std::int64_t> frames;
  std::optional<double> duration_s;
  int threads = 0;  // 0 = every core
  std::optional<std::uint64_t> seed;
  std::set<OutputKind> outputs = all_outputs();
  bool no_noise = false;
  bool resume = false;    // continue from the output folder's checkpoint (io/run_checkpoint.hpp)
  bool progress = false;  // a progress line on stderr
  TraceApi trace_api = TraceApi::stream;
};

struct RunReport {
  std::filesystem::path directory;
  std::int64_t frames = 0;  // of the whole flight
  std::uint64_t pulses = 0;
  std::int64_t first_frame = 0;  // where this run began: > 0 when it resumed an interrupted one
  double wall_s = 0.0;
  double pulses_per_s = 0.0;  // of the frames this run simulated
  double realtime_factor = 0.0;
  int threads = 0;
};

// Everything a run builds before its first frame: the scenario (with the options' seed and noise
// overrides), its local frame, scene and trajectory, the frame count, and the Embree scene and
// frame simulator. Built once (may throw); `owsim run` and `owsim bench` start from the same one.
// Not copyable or movable: the Embree scene and the simulator point into it.
struct FlightSetup {
  explicit FlightSetup(const RunOptions& options);
  FlightSetup(const FlightSetup&) = delete;
  FlightSetup& operator=(const FlightSetup&) = delete;

  Scenario scenario;
  LocalFrame local_frame;
  Scene scene;
  Trajectory trajectory;
  std::int64_t frames;        // frames 0..frames−1 (--frames, --duration or the scenario)
  Eigen::AlignedBox2d flown;  // east/north extent of the trajectory over those frames
  EmbreeDevice device;
  EmbreeScene embree_scene;  // terrain over `flown` widened by the counter's timeout range
  FrameSimulator simulator;  // with options.trace_api
};

// The output options of a run: --out (default out/<scenario name>/), --outputs, and a quick-look
// map over what was flown and built.
[[nodiscard]] FlightOutputOptions flight_output_options(const FlightSetup& setup,
                                                        const RunOptions& options);

// The frame pipeline of a run: frames `range` simulated by `simulator` (in parallel on the calling
// thread's TBB arena, one frame in flight per thread, at least 2) and fed to `outputs` in frame
// order with the aircraft's pose at each frame's first pulse. `frame_done` (may be empty) is told
// how many frames are done after each one.
void simulate_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                     const FlightRange& range, int threads, FlightOutputs& outputs,
                     const std::function<void(std::int64_t)>& frame_done = {});

// A whole `owsim run`. Keeps a checkpoint in the output folder while it runs; with
// options.resume, continues from the folder's checkpoint (throws owsim::Error naming it if it was
// written by a run with other output-changing options or inputs), or starts from frame 0 with a
// note on stderr if there is none.
RunReport run_flight_scenario(const RunOptions& options);

}  // namespace owsim::cli
