// The embedding shells' cost per frame (INTERFACE.md "Embedding"), all in one process on the
// corridor: the C++ facade (Simulation::simulate_frame into a reused Frame), the C ABI
// (owsim_simulate_frame into a reused owsim_frame, then its words and returns) and the Python
// module (sim.frame(k) through an embedded interpreter, then .words and .returns as numpy views).
// Each iteration is one frame, cycling over the first 12; items are pulses. The shells should add
// under 5 % to the C++ figure:
//   build/bench/bench_embedding --benchmark_repetitions=5 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>
#include <pybind11/embed.h>

#include <cstdint>
#include <string>

#include "owsim/owsim.h"
#include "owsim/owsim.hpp"

namespace owsim {
namespace {

constexpr std::int64_t kFrames = 12;
const std::string kCorridor = std::string(OWSIM_SOURCE_DIR) + "/examples/corridor.yaml";

void BM_FrameCpp(benchmark::State& state) {
  SimulationOptions options;
  options.frames = kFrames;
  const Simulation sim = Simulation::open(kCorridor, options);
  Frame frame;
  std::int64_t k = 0;
  for (auto _ : state) {
    sim.simulate_frame(k++ % kFrames, frame);
    benchmark::DoNotOptimize(frame.word_bytes().data());
    benchmark::DoNotOptimize(frame.returns().data());
  }
  state.SetItemsProcessed(state.iterations() * sim.pulses_per_frame());
}

void BM_FrameC(benchmark::State& state) {
  owsim_simulation_options options = owsim_simulation_options_default();
  options.frames = kFrames;
  owsim_simulation* sim = nullptr;
  if (owsim_simulation_open_with(kCorridor.c_str(), &options, &sim) != OWSIM_OK) {
    state.SkipWithError(owsim_last_error());
    return;
  }
  owsim_frame* frame = nullptr;
  std::int64_t k = 0;
  for (auto _ : state) {
    if (owsim_simulate_frame(sim, k++ % kFrames, &frame) != OWSIM_OK) {
      state.SkipWithError(owsim_last_error());
      break;
    }
    std::size_t bytes = 0, count = 0;
    benchmark::DoNotOptimize(owsim_frame_words(frame, &bytes));
    benchmark::DoNotOptimize(owsim_frame_returns(frame, &count));
  }
  state.SetItemsProcessed(state.iterations() * owsim_simulation_pulses_per_frame(sim));
  owsim_frame_release(frame);
  owsim_simulation_release(sim);
}

void BM_FramePython(benchmark::State& state) {
  namespace py = pybind11;
  static py::scoped_interpreter interpreter;  // one interpreter for the process
  py::module_::import("sys").attr("path").attr("insert")(0, OWSIM_PYTHON_DIR);
  py::globals()["path"] = kCorridor;
  py::globals()["frames"] = kFrames;
  py::exec(R"(
import owsim
sim = owsim.Simulation(path, frames=frames)
def frame(k):
    f = sim.frame(k)
    return f.words, f.returns
)");
  const py::object frame = py::globals()["frame"];
  std::int64_t k = 0;
  for (auto _ : state) {
    const py::object arrays = frame(k++ % kFrames);
    benchmark::DoNotOptimize(arrays.ptr());
  }
  state.SetItemsProcessed(state.iterations() *
                          py::globals()["sim"].attr("pulses_per_frame").cast<std::int64_t>());
}

// Interleaved so a burst of load on the machine hits all three alike.
BENCHMARK(BM_FrameCpp)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_FrameC)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_FramePython)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace
}  // namespace owsim
