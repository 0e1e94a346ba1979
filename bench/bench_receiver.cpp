// The receiver post-pass (engine/frame_simulator.hpp receive, sensor/receiver.hpp): threshold,
// return selection, range noise and counters for every pulse of the benchmark scenario's middle
// frame from its traced candidates — on one thread and on every core. Items are pulses.
#include <benchmark/benchmark.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <random>
#include <vector>

#include "bench/bench_fixture.hpp"
#include "sensor/receiver_noise.hpp"

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

// An echo within kSureEchoSigmas σ_n of the threshold is decided by u ≤ Φ((e − T)/σ_n): Arg 0 by
// erfc (standard_normal_cdf) every time, Arg 1 by the table with erfc only near the chord
// (uniform_within_standard_normal_cdf). Items are decisions; (u, x) spread as the draws are.
void BM_EchoDecision(benchmark::State& state) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> x_in(-kSureEchoSigmas, kSureEchoSigmas);
  std::vector<double> u(4096), x(4096);
  for (std::size_t i = 0; i < u.size(); ++i) {
    u[i] = unit(random);
    x[i] = x_in(random);
  }
  const bool tabled = state.range(0) != 0;
  for (auto _ : state) {
    int registered = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      registered += tabled ? uniform_within_standard_normal_cdf(u[i], x[i])
                           : u[i] <= standard_normal_cdf(x[i]);
    }
    benchmark::DoNotOptimize(registered);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(u.size()));
}
BENCHMARK(BM_EchoDecision)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
