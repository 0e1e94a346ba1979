// Word packing (io/recording/frame_words.hpp): one simulated frame of the benchmark scenario packed
// into MilOWS 64-bit words and, with the HELLAS pattern, into HELLAS 32-bit words. Items are
// pulses.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "bench/bench_fixture.hpp"
#include "io/recording/frame_words.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

void BM_PackMilowsFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  std::vector<std::uint64_t> words(f.traced.pulses.size());
  for (auto _ : state) {
    pack_milows_frame(f.traced.pulses, f.traced.returns, words);
    benchmark::DoNotOptimize(words.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * f.pulses_per_frame());
  state.SetBytesProcessed(state.iterations() * f.pulses_per_frame() * 8);
}
BENCHMARK(BM_PackMilowsFrame)->Unit(benchmark::kMicrosecond);

// The same frame's returns under the HELLAS pattern (same pulse count).
void BM_PackHellasFrame(benchmark::State& state) {
  const bench::BenchFixture& f = bench::bench_fixture();
  ScanParams scan = f.scenario.scan;
  scan.model = SensorModel::hellas;
  const FrameSweep sweep = frame_sweep(scan, f.scenario.seed, f.frame);
  std::vector<Pulse> pulses(static_cast<std::size_t>(scan.pulses_per_frame()));
  for (int k = 0; k < scan.pulses_per_frame(); ++k) {
    pulses[static_cast<std::size_t>(k)] = pulse_of_frame(scan, sweep, k);
  }
  std::vector<std::uint32_t> words(pulses.size());
  for (auto _ : state) {
    pack_hellas_frame(scan, sweep, pulses, f.traced.returns, words);
    benchmark::DoNotOptimize(words.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * scan.pulses_per_frame());
  state.SetBytesProcessed(state.iterations() * scan.pulses_per_frame() * 4);
}
BENCHMARK(BM_PackHellasFrame)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
