// Pose interpolation for a frame (sensor/trajectory.hpp, sensor/mounting.hpp): the aircraft's pose
// at every pulse's firing time of one frame of the benchmark scenario's trajectory, and the sensor
// placement (mount and lever arm) built from it — the per-pulse half of the ray build. Also the
// one-off cost of building the spline trajectory. Items are pulses (or records for the build).
#include <benchmark/benchmark.h>

#include "bench/bench_fixture.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

void BM_PoseAtFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const int pulses = f.pulses_per_frame();
  for (auto _ : state) {
    for (int k = 0; k < pulses; ++k) {
      benchmark::DoNotOptimize(f.trajectory.pose_at(pulse_time_s(f.scenario.scan, f.frame, k)));
    }
  }
  state.SetItemsProcessed(state.iterations() * pulses);
}
BENCHMARK(BM_PoseAtFrame)->Unit(benchmark::kMicrosecond);

void BM_PoseAndPlacementFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const int pulses = f.pulses_per_frame();
  for (auto _ : state) {
    for (int k = 0; k < pulses; ++k) {
      const Pose pose = f.trajectory.pose_at(pulse_time_s(f.scenario.scan, f.frame, k));
      benchmark::DoNotOptimize(sensor_placement(pose, f.scenario.mount, f.scenario.scan.model));
    }
  }
  state.SetItemsProcessed(state.iterations() * pulses);
}
BENCHMARK(BM_PoseAndPlacementFrame)->Unit(benchmark::kMicrosecond);

void BM_HeadingRate(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const double t = pulse_time_s(f.scenario.scan, f.frame, 0);
  for (auto _ : state) benchmark::DoNotOptimize(f.trajectory.heading_rate_deg_per_s(t));
}
BENCHMARK(BM_HeadingRate);

// The scenario's trajectory built from its source (waypoints planned and sampled, splines fitted).
void BM_LoadTrajectory(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  for (auto _ : state) benchmark::DoNotOptimize(load_trajectory(f.scenario, f.local_frame));
}
BENCHMARK(BM_LoadTrajectory)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace owsim
