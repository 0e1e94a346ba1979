#pragma once
// Everything a simulation builds before its first frame (DESIGN.md data flow, left half): the
// scenario with the options' seed and noise overrides, its local frame, scene and trajectory, the
// frame count, and the Embree scene and frame simulator. Built once (may throw owsim::Error);
// owsim::Simulation (owsim/simulation.hpp), `owsim run` and `owsim bench` all start from one.
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>

#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/frame_simulator.hpp"
#include "engine/frame_tracer.hpp"
#include "evaluation/frame_truth.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {

// How a Simulation is built from its scenario: what `owsim run` sets with --seed, --no-noise,
// --frames, --duration and --threads.
struct SimulationOptions {
  std::optional<std::uint64_t> seed;   // replaces the scenario's seed
  bool no_noise = false;               // range noise (σ = 0) and receiver noise off
  std::optional<std::int64_t> frames;  // frames 0..frames−1; default: the scenario's duration_s,
  std::optional<double> duration_s;    // else as many as its trajectory holds (not both)
  int threads = 0;  // at most this many threads work for the Simulation at once; 0 = every core
  // Co-simulation: an east/north box (local metres) where a host may fly besides the scenario's
  // own trajectory. The terrain is built over it too (widened by the counter's timeout range);
  // poses outside both are refused.
  std::optional<Eigen::AlignedBox2d> flight_area_enu_m;
  // Embree's query form (the same bytes in every form); unset, the widest packet the device
  // traces natively (widest_native_packet): 16 rays on AVX-512, whole `owsim run` processes on
  // two threads 15 alternating against 8: corridor 0.966, flat wires 0.981, real corridor 0.982
  // (one thread, corridor: 0.934). 8-ray packets against the stream, before: real corridor
  // 0.433 -> 0.411 s, flat wires 0.144 -> 0.141 s, corridor 0.253 -> 0.251 s.
  std::optional<TraceApi> trace_api;
};

// Not copyable or movable: the Embree scene and the simulator point into it.
struct FlightSetup {
  FlightSetup(Scenario scenario, const SimulationOptions& options);
  FlightSetup(const FlightSetup&) = delete;
  FlightSetup& operator=(const FlightSetup&) = delete;

  Scenario scenario;
  LocalFrame local_frame;
  Scene scene;
  Trajectory trajectory;
  std::int64_t frames;        // frames 0..frames−1 (options.frames, duration or the scenario)
  Eigen::AlignedBox2d flown;  // east/north extent of the trajectory over those frames
  Eigen::AlignedBox2d area;   // flown, merged with options.flight_area_enu_m
  EmbreeDevice device;
  EmbreeScene embree_scene;  // terrain over `area` widened by the counter's timeout range
  FrameSimulator simulator;  // with options.trace_api

  // Each frame's ground truth for truth.csv (evaluation/frame_truth.hpp): built on first use, so
  // runs without that output pay nothing for it. Thread-safe.
  [[nodiscard]] const FrameTruthModel& truth_model() const;

 private:
  mutable std::once_flag truth_built_;
  mutable std::unique_ptr<FrameTruthModel> truth_;
};

// The east/north box of the scene's objects (conductor vertices, cylinder bases).
[[nodiscard]] Eigen::AlignedBox2d scene_extent(const Scene& scene);

}  // namespace owsim
