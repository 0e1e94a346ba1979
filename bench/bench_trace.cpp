// The Embree trace of a frame (engine/frame_tracer.hpp): the middle frame's rays of the benchmark
// scenario through each query form — per ray (rtcIntersect1), stream (rtcIntersect1M) and packets
// of 8 (rtcIntersect8) — on one thread and on every core; and the brute-force reference tracer
// (engine/brute_force_tracer.hpp, the source's method) on a slice of the same rays. Items are the
// frame's pulses (the reference fiber's included, as `owsim bench` counts them) or, for brute
// force, the rays traced. BM_SimulateFrame is the whole frame simulation beside them.
#include <benchmark/benchmark.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <array>
#include <vector>

#include "bench/bench_fixture.hpp"
#include "engine/brute_force_tracer.hpp"

namespace owsim {
namespace {

// Args: query form (0 per_ray, 1 stream, 2 packet8, 3 packet16), threads (0 = every core).
void BM_TraceFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const TraceApi api = kTraceApis[static_cast<std::size_t>(state.range(0))];
  const int threads =
      state.range(1) > 0 ? static_cast<int>(state.range(1)) : tbb::info::default_concurrency();
  const FrameTracer tracer(f.embree_scene, api);
  std::vector<PulseCandidates> candidates(f.traced.rays.size());
  tbb::task_arena arena(threads);
  for (auto _ : state) {
    arena.execute([&] { tracer.trace(f.traced.rays, f.traced.active, candidates); });
    benchmark::DoNotOptimize(candidates.data());
  }
  state.SetItemsProcessed(state.iterations() * f.pulses_per_frame());
  state.SetLabel(std::string(to_string(api)));
  state.counters["threads"] = threads;
}
BENCHMARK(BM_TraceFrame)
    ->ArgsProduct({{0, 1, 2, 3}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The whole frame as the simulator does it (pattern, rays, the trace in the stream form, the
// receiver), against which BM_TraceFrame/1 is the floor. Arg: threads (0 = every core).
void BM_SimulateFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const int threads =
      state.range(0) > 0 ? static_cast<int>(state.range(0)) : tbb::info::default_concurrency();
  FrameResult out;
  tbb::task_arena arena(threads);
  for (auto _ : state) {
    arena.execute([&] { f.simulator.simulate(f.frame, f.trajectory, out); });
    benchmark::DoNotOptimize(out.returns.data());
  }
  state.SetItemsProcessed(state.iterations() * f.pulses_per_frame());
  state.counters["threads"] = threads;
}
BENCHMARK(BM_SimulateFrame)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Every 10th active ray of the frame through the brute-force tracer, on one thread.
void BM_BruteForceTrace(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const BruteForceTracer tracer(f.scene, f.embree_scene.terrain_mesh(), f.scenario.receiver);
  std::vector<const PulseRay*> slice;
  for (std::size_t k = 0; k < f.traced.rays.size(); k += 10) {
    if (f.traced.active[k] != 0) slice.push_back(&f.traced.rays[k]);
  }
  PulseCandidates candidates;
  for (auto _ : state) {
    for (const PulseRay* ray : slice) {
      tracer.trace(*ray, candidates);
      benchmark::DoNotOptimize(candidates);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(slice.size()));
}
BENCHMARK(BM_BruteForceTrace)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace owsim
