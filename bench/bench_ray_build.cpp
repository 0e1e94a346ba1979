// Ray build (engine/frame_simulator.hpp build_rays): one frame's pattern, per-pulse pose, sensor
// placement and ray direction, as the simulator does it before the trace — on one thread and on
// every core — and the ray direction alone from a fixed placement. Items are pulses.
#include <benchmark/benchmark.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include "bench/bench_fixture.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

// Arg: threads (0 = every core).
void BM_BuildRaysFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const int threads =
      state.range(0) > 0 ? static_cast<int>(state.range(0)) : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  FrameResult out;
  for (auto _ : state) {
    arena.execute([&] { f.simulator.build_rays(f.frame, f.trajectory, out); });
    benchmark::DoNotOptimize(out.rays.data());
  }
  state.SetItemsProcessed(state.iterations() * f.pulses_per_frame());
  state.counters["threads"] = threads;
}
BENCHMARK(BM_BuildRaysFrame)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond)->UseRealTime();

// ray_direction_enu for every pulse of the frame from one placement: the trigonometry of α and β.
void BM_RayDirectionFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const SensorPlacement placement =
      sensor_placement(f.trajectory.pose_at(f.traced.pulses.front().time_s), f.scenario.mount,
                       f.scenario.scan.model);
  std::int64_t rays = 0;
  for (auto _ : state) {
    for (const Pulse& pulse : f.traced.pulses) {
      if (pulse.reference) continue;
      benchmark::DoNotOptimize(ray_direction_enu(placement, pulse.alpha_deg, pulse.beta_deg));
      ++rays;
    }
  }
  state.SetItemsProcessed(rays);
}
BENCHMARK(BM_RayDirectionFrame)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
