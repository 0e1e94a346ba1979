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
#include "io/detections/flight_detections.hpp"
#include "io/run/flight_outputs.hpp"
#include "io/run/run_checkpoint.hpp"
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
  // Before the first frame: reading the scenario, building the scene, the BVH and the simulator,
  // opening the outputs (and reading a checkpoint). summary.json's `setup_s`.
  double setup_s = 0.0;
  double wall_s = 0.0;        // the frames: from the first frame's start to the last one's end
  double pulses_per_s = 0.0;  // of the frames this run simulated
  double realtime_factor = 0.0;
  int threads = 0;    // per process
  int processes = 1;  // of a distributed run (distributed/)
};

// The output folder and files of a run: `out` (default out/<scenario name>/), `outputs`, and a
// quick-look map over what was flown and built.
[[nodiscard]] FlightOutputOptions flight_output_options(
    const FlightSetup& setup, const std::optional<std::filesystem::path>& out,
    const std::set<OutputKind>& outputs);

// What makes a run's output bytes (io/run/run_checkpoint.hpp `run`): owsim's version, the
// scenario's text (`source_hash`) and the files it reads, and the options that change bytes. Not
// the thread or process count, which change none.
[[nodiscard]] nlohmann::json run_fingerprint(const FlightSetup& setup,
                                             const SimulationOptions& simulation,
                                             const std::string& source_hash,
                                             const RunOptions& options);

// flight_output_options of a run with checkpoints by `fingerprint` (run_fingerprint); a null
// fingerprint (a scenario built in code) keeps none, and throws owsim::Error if options.resume.
[[nodiscard]] FlightOutputOptions run_output_options(const FlightSetup& setup,
                                                     const nlohmann::json& fingerprint,
                                                     const RunOptions& options);

// The checkpoint in the folder of `output_options` that a resumed run of `frames` frames continues
// from, compared with this run's fingerprint (output_options.checkpoint_run); std::nullopt (and a
// notice) if the folder has none. Throws owsim::Error naming the file if it is of another run.
[[nodiscard]] std::optional<RunCheckpoint> checkpoint_to_resume(
    const FlightOutputOptions& output_options, std::int64_t frames, const RunOptions& options);

// Frames `range` simulated by `simulator` (in parallel on the calling thread's TBB arena, one
// frame in flight per thread), encoded by `encoder` where they were simulated, and handed to
// `sink` in frame order, one at a time. An encoding error is thrown, in frame order. With
// FrameRecordScope::block (only when the encoder does not read_frame_records) the frames given to
// `sink` hold their index and sweep but no per-pulse records.
// With `detections`, each frame's words (the encoder must encode them: output d64) are decoded for
// the detector where the frame was simulated, and the detector is fed in frame order before `sink`.
void encode_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                   const FlightRange& range, int threads, const FrameEncoder& encoder,
                   const std::function<void(const FrameView&, const FrameEncoding&)>& sink,
                   FrameRecordScope records = FrameRecordScope::frame,
                   FlightDetections* detections = nullptr);

// Frames `range` simulated by `simulator` (in parallel on the calling thread's TBB arena, one
// frame in flight per thread) and fed to `outputs` in frame order. `frame_done` (may be empty) is
// told how many frames are done after each one.
void simulate_frames(const FrameSimulator& simulator, const FlightSetup& setup,
                     const FlightRange& range, int threads, FlightOutputs& outputs,
                     const std::function<void(std::int64_t)>& frame_done = {},
                     FlightDetections* detections = nullptr);

// The report of a run of `setup` that began at `first_frame` (> 0: resumed) and simulated the rest
// in `wall_s` with `processes` × `threads` workers.
[[nodiscard]] RunReport run_report(const FlightSetup& setup, const std::filesystem::path& directory,
                                   std::int64_t first_frame, double wall_s, int threads,
                                   int processes);
// What summary.json says of the run besides its frames (INTERFACE.md): scenario, seed, wall time,
// pulses/s, real-time factor, threads, processes, owsim version.
[[nodiscard]] nlohmann::json run_facts(const Scenario& scenario, const RunReport& report);

// detections.csv of a finished distributed run in `directory` (output `detections`): the
// reference detector over the word file the run wrote, as `owsim detect` runs it on the folder —
// the folder's scenario.yaml when the run wrote one (`flown` not empty), else `setup`'s scenario.
// A run in one process writes the same bytes as it goes (io/detections/flight_detections.hpp).
void write_run_detections(const FlightSetup& setup, const FlownScenario& flown,
                          const std::filesystem::path& directory);

// A whole run on the calling thread's TBB arena with `threads` workers. `source_hash` identifies
// the scenario's text (its file or the text it was opened from): it goes into the checkpoint, so
// --resume refuses a checkpoint of another scenario; empty (a scenario built in code) → a run
// that cannot be resumed. Keeps a checkpoint in the output folder while it runs; with
// options.resume, continues from the folder's checkpoint (throws owsim::Error naming it if it was
// written by a run with other output-changing options or inputs), or starts from frame 0 with a
// notice if there is none. `build_s`: the time building `setup` took, for RunReport::setup_s.
// `flown`: scenario.yaml and the files it names (an empty text: none is written).
[[nodiscard]] RunReport run_flight_outputs(const FlightSetup& setup,
                                           const SimulationOptions& simulation,
                                           const std::string& source_hash,
                                           const FlownScenario& flown, const RunOptions& options,
                                           int threads, double build_s);

}  // namespace owsim
