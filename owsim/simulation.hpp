#pragma once
// owsim::Simulation — the library's one entry point (INTERFACE.md "Embedding"): a scenario (a file,
// YAML text, or a Scenario built in code) set up once into its scene, trajectory and Embree scene,
// then simulated frame by frame or run whole into output files. `owsim run`, the C ABI
// (owsim/owsim.h) and the Python module are thin shells over it, so what they return equals what
// `owsim run` writes, byte for byte.
//
// Errors: every fallible call throws owsim::Error (geometry/error.hpp) with one line naming the
// file, line or key and the problem — owsim::FileError when a file cannot be opened, read or
// written. A scenario built in code gets the same checks as one read from YAML (validate_scenario).
//
// Threading contract:
//  - A Simulation does not change after it is built: every member function is const and may be
//    called concurrently from any number of host threads (simulate_frame each with its own Frame;
//    run each into its own folder). Several Simulations may live side by side.
//  - owsim starts no threads of its own. Each call runs its parallel work in the Simulation's TBB
//    task arena of SimulationOptions::threads slots (0: every core), served by TBB's process-wide
//    worker pool; the calling thread takes part and the call returns when the work is done. So a
//    host limits owsim with SimulationOptions::threads per Simulation, and the whole process (owsim
//    and everything else on TBB) with tbb::global_control(max_allowed_parallelism).
//  - RunOptions::progress and ::notice are called from one thread at a time, possibly a TBB worker.
//  - A Frame is a plain value: read it from any number of threads; refill it from one.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/scenario/scenario.hpp"
#include "owsim/flight_run.hpp"
#include "owsim/flight_setup.hpp"
#include "owsim/frame.hpp"

namespace owsim {

// One sample of the aircraft's state pushed by a host flight simulator (co-simulation): time on
// the scenario's trajectory clock, position in the scenario's local East-North-Up frame (metres
// from its origin; Simulation::enu_from_geodetic converts WGS-84), attitude in degrees (roll right
// wing down, pitch nose up, true heading; SENSOR-SPEC §4).
struct PoseSample {
  double time_s = 0;
  double e_m = 0, n_m = 0, u_m = 0;
  double roll_deg = 0, pitch_deg = 0, heading_deg = 0;
};

class Simulation {
 public:
  // A scenario file (INTERFACE.md "Scenario file"); relative paths in it are resolved against its
  // folder.
  [[nodiscard]] static Simulation open(const std::filesystem::path& scenario_file,
                                       const SimulationOptions& options = {});
  // YAML text in memory: `name` stands for the file in errors, gives the default scenario name
  // (its stem) and anchors relative paths; it need not exist.
  [[nodiscard]] static Simulation from_yaml(std::string_view yaml,
                                            const std::filesystem::path& name = "scenario.yaml",
                                            const SimulationOptions& options = {});
  // A scenario built in code (io/scenario/scenario.hpp: plain structs with the spec's defaults),
  // checked by validate_scenario first. Its runs keep no checkpoint (RunOptions::resume is
  // refused).
  [[nodiscard]] static Simulation from_scenario(Scenario scenario,
                                                const SimulationOptions& options = {});

  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  // The scenario as simulated (the options' seed and noise overrides applied).
  [[nodiscard]] const Scenario& scenario() const;
  [[nodiscard]] SensorModel model() const;
  // Frames 0..frame_count()−1 along the scenario's trajectory (SimulationOptions frames/duration).
  [[nodiscard]] std::int64_t frame_count() const;
  [[nodiscard]] int pulses_per_frame() const;
  // When frame k's first and last pulses fire, seconds on the trajectory's clock.
  [[nodiscard]] double frame_start_s(std::int64_t frame) const;
  [[nodiscard]] double frame_end_s(std::int64_t frame) const;
  // The id of each object, by ReturnRecord::object ("<span>/<n>" for a conductor, "terrain" last).
  [[nodiscard]] const std::vector<std::string>& object_ids() const;
  // WGS-84 → the local ENU frame of the scenario (for PoseSample).
  [[nodiscard]] PoseSample enu_from_geodetic(double lat_deg, double lon_deg, double h_m) const;

  // Frame k (0 ≤ k < frame_count()) along the scenario's trajectory.
  [[nodiscard]] Frame simulate_frame(std::int64_t frame) const;
  void simulate_frame(std::int64_t frame, Frame& out) const;
  // Co-simulation: frame k (any k ≥ 0) with the aircraft's poses pushed by the host, interpolated
  // as the trajectory module does (natural cubic splines through the samples, heading unwrapped;
  // no smoothing). The samples' times must increase and cover [frame_start_s(k), frame_end_s(k)];
  // their positions must lie in the scenario's flown area or SimulationOptions::flight_area_enu_m.
  // Throws owsim::Error "poses: …" otherwise.
  [[nodiscard]] Frame simulate_frame(std::int64_t frame, std::span<const PoseSample> poses) const;
  void simulate_frame(std::int64_t frame, std::span<const PoseSample> poses, Frame& out) const;

  // What `owsim run` does: every frame into the output files, with checkpoints and resume.
  RunReport run(const RunOptions& options = {}) const;

  // The workers owsim may use at once (SimulationOptions::threads, or every core).
  [[nodiscard]] int threads() const;
  // Runs `work` on those workers' task arena (where run() simulates), for drivers below the facade
  // (distributed/).
  void in_arena(const std::function<void()>& work) const;
  // scenario.yaml of its runs: the scenario's YAML as flown, with the copies of the files it
  // names (io/scenario/scenario_as_flown.hpp); empty for a scenario built in code, whose runs
  // write none.
  [[nodiscard]] const FlownScenario& scenario_as_flown() const;
  // What makes a run's output bytes (io/run/run_checkpoint.hpp `run`), as run() keeps it in its
  // checkpoint; null for a scenario built in code, whose runs keep none.
  [[nodiscard]] nlohmann::json run_fingerprint(const RunOptions& options) const;
  // Everything the simulation built (scene, trajectory, Embree scene, frame simulator), for tools
  // that go below the facade (`owsim bench`).
  [[nodiscard]] const FlightSetup& setup() const;
  // Seconds building it took: reading the scenario, the scene, the BVH and the simulator.
  [[nodiscard]] double build_s() const;

 private:
  struct State;
  explicit Simulation(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace owsim
