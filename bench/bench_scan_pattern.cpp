// The scan pattern of a frame (sensor/scan_pattern.hpp): every pulse's time, fiber, α, β, encoder
// word and gates computed from (frame, pulse), for MilOWS and HELLAS. Items are pulses.
#include <benchmark/benchmark.h>

#include <vector>

#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

ScanParams scan_of(SensorModel model) {
  ScanParams scan;
  scan.model = model;
  return scan;
}

void BM_FrameSweep(benchmark::State& state) {
  const ScanParams scan;
  std::int64_t frame = 0;
  for (auto _ : state) benchmark::DoNotOptimize(frame_sweep(scan, 42, frame++));
}
BENCHMARK(BM_FrameSweep);

// Arg 0: MilOWS, 1: HELLAS.
void BM_ScanPatternFrame(benchmark::State& state) {
  const ScanParams scan = scan_of(state.range(0) == 0 ? SensorModel::milows : SensorModel::hellas);
  const int pulses = scan.pulses_per_frame();
  std::vector<Pulse> out(static_cast<std::size_t>(pulses));
  std::int64_t frame = 0;
  for (auto _ : state) {
    const FrameSweep sweep = frame_sweep(scan, 42, frame++);
    for (int k = 0; k < pulses; ++k)
      out[static_cast<std::size_t>(k)] = pulse_of_frame(scan, sweep, k);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * pulses);
  state.SetLabel(state.range(0) == 0 ? "milows" : "hellas");
}
BENCHMARK(BM_ScanPatternFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The time tag alone (a floor and a modulus per pulse, with its boundary guard).
void BM_MilowsTimeTag(benchmark::State& state) {
  const ScanParams scan;
  const int pulses = scan.pulses_per_frame();
  for (auto _ : state) {
    for (int k = 0; k < pulses; ++k)
      benchmark::DoNotOptimize(milows_time_tag(pulse_time_s(scan, 7, k)));
  }
  state.SetItemsProcessed(state.iterations() * pulses);
}
BENCHMARK(BM_MilowsTimeTag)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
