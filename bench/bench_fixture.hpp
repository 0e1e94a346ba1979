#pragma once
// The scene every micro-benchmark in bench/ runs on: examples/corridor.yaml (the benchmark scene
// of DESIGN.md "Performance model": a 2 km corridor, 59 conductors, 400 trees, poles, flat
// ground), or the scenario named by the environment variable OWSIM_BENCH_SCENARIO. Built the way
// `owsim run` builds it (scene, trajectory, Embree scene over what the flight can reach, frame
// simulator), once per benchmark program, on first use. `frame` is the middle frame of the
// scenario's flight; `traced` holds it simulated whole (pattern, rays, returns) and `candidates`
// what its trace found, for the stages after the trace. Bench code only.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/frame_simulator.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/scenario/scenario.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/trajectory.hpp"

namespace owsim::bench {

// examples/corridor.yaml beside this file's folder, unless OWSIM_BENCH_SCENARIO names another.
inline std::filesystem::path bench_scenario_path() {
  if (const char* chosen = std::getenv("OWSIM_BENCH_SCENARIO"); chosen != nullptr && *chosen) {
    return chosen;
  }
  return std::filesystem::path(__FILE__).parent_path().parent_path() / "examples" / "corridor.yaml";
}

// Frames of the scenario's flight: its duration_s, else as many as the trajectory holds.
inline std::int64_t flight_frames(const Scenario& scenario, const Trajectory& trajectory) {
  const double frame_s = scenario.scan.frame_duration_s();
  const double seconds =
      scenario.trajectory.duration_s.value_or(trajectory.end_s() - scenario.scan.start_s);
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(seconds / frame_s)));
}

// East/north extent the sensor can reach: the flight's frame starts widened by the timeout range.
inline Eigen::AlignedBox2d reach_of_flight(const Scenario& scenario, const Trajectory& trajectory,
                                           std::int64_t frames, double max_range_m) {
  Eigen::AlignedBox2d box;
  for (std::int64_t f = 0; f <= frames; ++f) {
    const double t = std::min(pulse_time_s(scenario.scan, f, 0), trajectory.end_s());
    box.extend(trajectory.pose_at(t).position_enu_m.head<2>());
  }
  box.min().array() -= max_range_m;
  box.max().array() += max_range_m;
  return box;
}

struct BenchFixture {
  BenchFixture()
      : scenario(load_scenario(bench_scenario_path())),
        local_frame(scenario.origin),
        scene(build_scene(scenario)),
        trajectory(load_trajectory(scenario, local_frame)),
        frames(flight_frames(scenario, trajectory)),
        frame(frames / 2),
        max_range_m(timeout_range_m(scenario.receiver.counter)),
        embree_scene(device, scene, scenario.receiver,
                     reach_of_flight(scenario, trajectory, frames, max_range_m), max_range_m),
        simulator(
            FrameSimulatorParams{scenario.scan, scenario.receiver, scenario.mount, scenario.seed},
            embree_scene, TraceApi::stream) {
    simulator.simulate(frame, trajectory, traced);
    candidates.resize(traced.rays.size());
    simulator.tracer().trace(traced.rays, traced.active, candidates);
  }
  BenchFixture(const BenchFixture&) = delete;
  BenchFixture& operator=(const BenchFixture&) = delete;

  [[nodiscard]] int pulses_per_frame() const { return scenario.scan.pulses_per_frame(); }

  Scenario scenario;
  LocalFrame local_frame;
  Scene scene;
  Trajectory trajectory;
  std::int64_t frames;  // of the scenario's flight
  std::int64_t frame;   // the frame the benchmarks use: the middle one
  double max_range_m;   // the counter's timeout range
  EmbreeDevice device;
  EmbreeScene embree_scene;
  FrameSimulator simulator;
  FrameResult traced;                       // `frame` simulated whole
  std::vector<PulseCandidates> candidates;  // what the trace of `traced` found
};

// The program's fixture, built on first use.
inline const BenchFixture& bench_fixture() {
  static const BenchFixture fixture;
  return fixture;
}

}  // namespace owsim::bench
