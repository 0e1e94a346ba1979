// The receiver post-pass (engine/frame_simulator.hpp receive, sensor/receiver.hpp): threshold,
// return selection, range noise and counters for every pulse of the benchmark scenario's middle
// frame from its traced candidates — on one thread and on every core. Items are pulses.
#include <benchmark/benchmark.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include "bench/bench_fixture.hpp"

namespace owsim {
namespace {

// Arg: threads (0 = every core).
void BM_ReceiveFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  const int threads =
      state.range(0) > 0 ? static_cast<int>(state.range(0)) : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  FrameResult frame = f.traced;
  for (auto _ : state) {
    arena.execute([&] { f.simulator.receive(frame, f.candidates); });
    benchmark::DoNotOptimize(frame.returns.data());
  }
  state.SetItemsProcessed(state.iterations() * f.pulses_per_frame());
  state.counters["threads"] = threads;
}
BENCHMARK(BM_ReceiveFrame)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond)->UseRealTime();

// select_returns alone for the frame's pulses that have a candidate, on one thread.
void BM_SelectReturns(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  std::array<Candidate, PulseCandidates::kMaxWires + 1> gathered;
  std::int64_t pulses = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < f.candidates.size(); ++k) {
      const std::span<Candidate> candidates = f.candidates[k].gather(gathered);
      if (candidates.empty()) continue;
      benchmark::DoNotOptimize(select_returns(candidates, f.scenario.receiver, f.scenario.seed,
                                              f.frame, static_cast<int>(k)));
      ++pulses;
    }
  }
  state.SetItemsProcessed(pulses);
}
BENCHMARK(BM_SelectReturns)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
