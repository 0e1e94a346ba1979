#pragma once
// A whole flight into output files (INTERFACE.md "`owsim run` outputs"): the frame pipeline of
// engine/flight_pipeline.hpp feeding io/run/flight_outputs.hpp, with the run checkpoint that
// --resume continues from. What owsim::Simulation::run does; `owsim bench` times simulate_frames
// alone.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "engine/flight_pipeline.hpp"
#include "io/run/flight_outputs.hpp"
#include "owsim/flight_setup.hpp"

namespace owsim {

// How far a run is, after each frame.
struct RunProgress {
  std::int64_t frames_done = 0;   // frames 0..frames_done−1 are in the outputs
  std::int64_t frames_total = 0;  // of the whole flight
  std::int64_t first_frame = 0;   // where this run began (> 0 when it resumed)
  double elapsed_s = 0.0;         // wall time since this run began simulating
};

struct RunOptions {
  std::optional<std::filesystem::path> out;  // default out/<scenario name>/
  std::set<OutputKind> outputs = all_outputs();
  bool resume = false;  // continue from the output folder's checkpoint (io/run/run_checkpoint.hpp)
  // Called after every frame, in frame order, from one thread at a time (a worker's, not
  // necessarily the caller's). An exception it throws stops the run; the outputs are removed.
  std::function<void(const RunProgress&)> progress;
  // One-line notes a command would show (e.g. "no checkpoint …: starting from frame 0").
  std::function<void(std::string_view)> notice;
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

// The output folder and files of a run: `out` (default out/<scenario name>/), `outputs`, and a
// quick-look map over what was flown and built.
[[nodiscard]] FlightOutputOptions flight_output_options(
    const FlightSetup& setup, const std::optional<std::filesystem::path>& out,
    const std::set<OutputKind>& outputs);

// Frames `range` simulated by `simulator` (in parallel on the calling thread's TBB arena, one
// frame in flight per thread) and fed to `outputs` in frame order. `frame_done` (may be empty) is
// told how many frames are done after each one.
void simulate_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                     const FlightRange& range, int threads, FlightOutputs& outputs,
                     const std::function<void(std::int64_t)>& frame_done = {});

// A whole run on the calling thread's TBB arena with `threads` workers. `source_hash` identifies
// the scenario's text (its file or the text it was opened from): it goes into the checkpoint, so
// --resume refuses a checkpoint of another scenario; empty (a scenario built in code) → a run
// that cannot be resumed. Keeps a checkpoint in the output folder while it runs; with
// options.resume, continues from the folder's checkpoint (throws owsim::Error naming it if it was
// written by a run with other output-changing options or inputs), or starts from frame 0 with a
// notice if there is none.
[[nodiscard]] RunReport run_flight_outputs(const FlightSetup& setup,
                                           const SimulationOptions& simulation,
                                           const std::string& source_hash,
                                           const RunOptions& options, int threads);

}  // namespace owsim
