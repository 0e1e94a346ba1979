#include "owsim/simulation.hpp"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/input_file.hpp"
#include "io/run/run_checkpoint.hpp"
#include "io/scenario/scenario_as_flown.hpp"
#include "io/scenario/scenario_check.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

// A frame number a time can be asked of: frames start at 0.
std::int64_t frame_number(std::int64_t frame) {
  if (frame < 0) throw input_error("frame", "must be ≥ 0, got " + std::to_string(frame));
  return frame;
}

using Clock = std::chrono::steady_clock;

// The east/north positions of the recorded trajectory over the flight's time window (start_s,
// duration_s) and one second around: a DEM is then read for the flight's reach only.
std::vector<Eigen::Vector2d> recorded_track(const Scenario& scenario, const LocalFrame& frame) {
  const NavTrack track = load_nav_track(scenario, frame);
  const TrajectorySpec& spec = scenario.trajectory;
  const double first_s = spec.start_s - 1.0;
  const double last_s = spec.duration_s ? spec.start_s + *spec.duration_s + 1.0
                                        : std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector2d> positions;
  for (std::size_t i = 0; i < track.position_enu_m.size() && i < track.time_s.size(); ++i) {
    if (track.time_s[i] < first_s || track.time_s[i] > last_s) continue;
    positions.push_back(track.position_enu_m[i].head<2>());
  }
  return positions;
}

int worker_count(const SimulationOptions& options) {
  return options.threads > 0 ? options.threads : tbb::info::default_concurrency();
}

// A scenario built in code, checked and completed as the loader completes what it reads.
Scenario checked(Scenario scenario) {
  if (scenario.name.empty() && !scenario.path.empty())
    scenario.name = scenario.path.stem().string();
  scenario.scan.counter = scenario.receiver.counter;
  scenario.scan.start_s = scenario.trajectory.start_s;
  try {
    validate_scenario(scenario);
  } catch (const FileError&) {
    throw;
  } catch (const Error& error) {
    throw input_error(scenario.name.empty() ? "scenario" : scenario.name, error.what());
  }
  return scenario;
}

std::string text_of(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", value);
  return text;
}

// The host's samples as a trajectory over frame `frame`; throws "poses: …" for samples that do
// not cover the frame or leave the area the scene was built for.
Trajectory pushed_trajectory(const FlightSetup& setup, std::int64_t frame,
                             std::span<const PoseSample> poses) {
  if (frame < 0) throw input_error("frame", "must be ≥ 0, got " + std::to_string(frame));
  const ScanParams& scan = setup.scenario.scan;
  const double first = pulse_time_s(scan, frame, 0);
  const double last = pulse_time_s(scan, frame, scan.pulses_per_frame() - 1);
  if (poses.size() < 2) {
    throw input_error("poses", "need at least 2 samples covering frame " + std::to_string(frame) +
                                   " (" + text_of(first) + "–" + text_of(last) + " s), got " +
                                   std::to_string(poses.size()));
  }
  NavTrack track;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const PoseSample& pose = poses[i];
    const Eigen::Vector3d position(pose.e_m, pose.n_m, pose.u_m);
    if (setup.scenario.scene.terrain.kind != TerrainKind::none && position.allFinite() &&
        !setup.area.contains(position.head<2>())) {
      throw input_error("poses[" + std::to_string(i) + "]",
                        "position (" + text_of(pose.e_m) + ", " + text_of(pose.n_m) +
                            ") m lies outside the area the terrain was built for; give the "
                            "simulation's flight_area_enu_m option (C++ SimulationOptions, C "
                            "owsim_simulation_options)");
    }
    track.time_s.push_back(pose.time_s);
    track.position_enu_m.push_back(position);
    track.attitude.push_back(Attitude{pose.roll_deg, pose.pitch_deg, pose.heading_deg});
  }
  if (!(poses.front().time_s <= first && poses.back().time_s >= last)) {
    throw input_error("poses", "cover " + text_of(poses.front().time_s) + "–" +
                                   text_of(poses.back().time_s) + " s; frame " +
                                   std::to_string(frame) + " needs " + text_of(first) + "–" +
                                   text_of(last) + " s");
  }
  TrajectoryOptions options;
  options.smoothing.window = 1;  // the host's poses are taken as exact
  options.irs_noise = setup.scenario.trajectory.irs_noise;
  options.seed = setup.scenario.seed;
  try {
    return Trajectory(track, setup.local_frame, options);
  } catch (const Error& error) {
    // The trajectory says "trajectory record <i>: <problem>"; the host pushed poses[<i>].
    constexpr std::string_view kRecord = "trajectory record ";
    std::string message = error.what();
    if (message.starts_with(kRecord)) {
      const std::size_t colon = message.find(':');
      message = "poses[" + message.substr(kRecord.size(), colon - kRecord.size()) + "]" +
                message.substr(colon);
    }
    throw Error(message);
  }
}

}  // namespace

struct Simulation::State {
  // `start`: when building it began (before the scenario was read).
  // `yaml`: the scenario's text (empty for a scenario built in code), read from `path`.
  State(Scenario scenario, const SimulationOptions& options_in, std::string hash,
        Clock::time_point start, std::string_view yaml = {}, const std::filesystem::path& path = {})
      : options(options_in),
        source_hash(std::move(hash)),
        setup(std::move(scenario), options),
        flown(yaml.empty() ? FlownScenario() : as_flown(yaml, path)),
        geodesy(setup.local_frame),
        threads(worker_count(options)),
        arena(threads),
        build_s(std::chrono::duration<double>(Clock::now() - start).count()) {}

  SimulationOptions options;
  std::string source_hash;  // of the scenario's text; empty for a scenario built in code
  FlightSetup setup;
  FlownScenario flown;   // scenario.yaml of its runs; empty for a scenario built in code
  GeodesyCells geodesy;  // places the frames' returns on WGS-84, shared by every frame
  int threads;
  mutable tbb::task_arena arena;
  // object_ids(), built on first use: a run that never asks keeps no copy of a million ids.
  mutable std::once_flag ids_built;
  mutable std::vector<std::string> ids;
  double build_s;  // reading the scenario and building the scene, the BVH and the simulator

  [[nodiscard]] FlownScenario as_flown(std::string_view yaml,
                                       const std::filesystem::path& path) const {
    FlownOverrides overrides;
    overrides.seed = setup.scenario.seed;
    overrides.no_noise = options.no_noise;
    if (options.frames || options.duration_s) {
      overrides.duration_s =
          static_cast<double>(setup.frames) * setup.scenario.scan.frame_duration_s();
    }
    return owsim::scenario_as_flown(yaml, path, overrides, setup.scenario.input_files);
  }

  void simulate(std::int64_t frame, const PoseSource& poses, Frame& out) const {
    arena.execute([&] {
      setup.simulator.simulate(frame, poses, out.result_);
      out.encode(setup.scenario.scan, geodesy);
    });
  }
};

Simulation::Simulation(std::unique_ptr<State> state) : state_(std::move(state)) {}
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

Simulation Simulation::open(const std::filesystem::path& scenario_file,
                            const SimulationOptions& options) {
  const auto start = Clock::now();
  Scenario scenario = load_scenario(scenario_file, recorded_track);
  const std::string yaml = read_input_file(scenario_file, "scenario file", kMaxScenarioBytes);
  return Simulation(std::make_unique<State>(std::move(scenario), options, ContentHash::hex_of(yaml),
                                            start, yaml, scenario_file));
}

Simulation Simulation::from_yaml(std::string_view yaml, const std::filesystem::path& name,
                                 const SimulationOptions& options) {
  const auto start = Clock::now();
  Scenario scenario = load_scenario_text(yaml, name, recorded_track);
  return Simulation(std::make_unique<State>(std::move(scenario), options, ContentHash::hex_of(yaml),
                                            start, yaml, name));
}

Simulation Simulation::from_scenario(Scenario scenario, const SimulationOptions& options) {
  const auto start = Clock::now();
  return Simulation(
      std::make_unique<State>(checked(std::move(scenario)), options, std::string(), start));
}

double Simulation::build_s() const { return state_->build_s; }
const Scenario& Simulation::scenario() const { return state_->setup.scenario; }
SensorModel Simulation::model() const { return state_->setup.scenario.scan.model; }
std::int64_t Simulation::frame_count() const { return state_->setup.frames; }
int Simulation::pulses_per_frame() const { return state_->setup.scenario.scan.pulses_per_frame(); }
double Simulation::frame_start_s(std::int64_t frame) const {
  return pulse_time_s(state_->setup.scenario.scan, frame_number(frame), 0);
}
double Simulation::frame_end_s(std::int64_t frame) const {
  return pulse_time_s(state_->setup.scenario.scan, frame_number(frame), pulses_per_frame() - 1);
}
const std::vector<std::string>& Simulation::object_ids() const {
  std::call_once(state_->ids_built, [&] { state_->ids = owsim::object_ids(state_->setup.scene); });
  return state_->ids;
}
int Simulation::threads() const { return state_->threads; }
const FlightSetup& Simulation::setup() const { return state_->setup; }

PoseSample Simulation::enu_from_geodetic(double lat_deg, double lon_deg, double h_m) const {
  const Eigen::Vector3d enu = state_->setup.local_frame.enu_from_geodetic({lat_deg, lon_deg, h_m});
  PoseSample sample;
  sample.e_m = enu.x();
  sample.n_m = enu.y();
  sample.u_m = enu.z();
  return sample;
}

Frame Simulation::simulate_frame(std::int64_t frame) const {
  Frame out;
  simulate_frame(frame, out);
  return out;
}

void Simulation::simulate_frame(std::int64_t frame, Frame& out) const {
  if (frame < 0 || frame >= frame_count()) {
    throw input_error("frame", std::to_string(frame) +
                                   " is out of range: the flight has frames 0.." +
                                   std::to_string(frame_count() - 1));
  }
  state_->simulate(frame, state_->setup.trajectory, out);
}

Frame Simulation::simulate_frame(std::int64_t frame, std::span<const PoseSample> poses) const {
  Frame out;
  simulate_frame(frame, poses, out);
  return out;
}

void Simulation::simulate_frame(std::int64_t frame, std::span<const PoseSample> poses,
                                Frame& out) const {
  const Trajectory trajectory = pushed_trajectory(state_->setup, frame, poses);
  state_->simulate(frame, trajectory, out);
}

void Simulation::in_arena(const std::function<void()>& work) const { state_->arena.execute(work); }

const FlownScenario& Simulation::scenario_as_flown() const { return state_->flown; }

nlohmann::json Simulation::run_fingerprint(const RunOptions& options) const {
  if (state_->source_hash.empty()) return nullptr;
  return owsim::run_fingerprint(state_->setup, state_->options, state_->source_hash, options);
}

RunReport Simulation::run(const RunOptions& options) const {
  return state_->arena.execute([&] {
    return run_flight_outputs(state_->setup, state_->options, state_->source_hash, state_->flown,
                              options, state_->threads, state_->build_s);
  });
}

}  // namespace owsim
