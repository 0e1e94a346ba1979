// Whole-process time of `owsim` (issue 16: start-up before any work), each command run as its own
// process, fork to reaped exit, in one run beside the yardstick, a plain C++ program:
//   PlainCpp      the plain C++ program (bench/plain_program.cpp)
//   Version       owsim --version
//   OneFrame      owsim run examples/corridor.yaml --frames 1 --outputs d64,summary
//   Flight30s     owsim run examples/corridor.yaml --duration 30 --outputs d64,summary
// Counters: vs_plain = the command's mean wall time / the plain program's (measured first, in the
// same run); for the runs, loop_s = summary.json's wall_s (the simulation loop) and
// process_vs_loop = whole process / loop.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "child_process.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using bench::ChildRun;

double plain_wall_s = 0.0;

fs::path plain_program() {
  return fs::read_symlink("/proc/self/exe").parent_path() / "plain_cpp_program";
}

// Runs `program arguments` once per iteration; sets the manual time and vs_plain. Returns false
// (and marks the benchmark failed) if a run did not exit 0.
bool time_processes(benchmark::State& state, const fs::path& program,
                    const std::vector<std::string>& arguments, const fs::path& out = {}) {
  double total_s = 0.0;
  for (auto _ : state) {
    const ChildRun run = bench::run_child(program, arguments);
    if (run.exit_status != 0) {
      state.SkipWithError((program.string() + " failed: run it by hand to see why").c_str());
      return false;
    }
    state.SetIterationTime(run.wall_s);
    total_s += run.wall_s;
    if (!out.empty()) {
      state.PauseTiming();
      std::error_code ignored;
      fs::remove_all(out, ignored);
      state.ResumeTiming();
    }
  }
  const double mean_s = total_s / static_cast<double>(state.iterations());
  if (plain_wall_s > 0.0) state.counters["vs_plain"] = mean_s / plain_wall_s;
  state.counters["process_s"] = mean_s;
  return true;
}

void BM_PlainCpp(benchmark::State& state) {
  if (time_processes(state, plain_program(), {})) {
    plain_wall_s = state.counters["process_s"];
  }
}

void BM_Version(benchmark::State& state) {
  time_processes(state, bench::owsim_program(), {"--version"});
}

// `owsim run corridor.yaml` with `extent` ({"--frames", "1"} or {"--duration", "30"}); reads
// the loop time from the last run's summary.json before its folder is removed.
void time_run(benchmark::State& state, const std::vector<std::string>& extent) {
  const bench::ScratchFolder folder;
  const fs::path out = folder.path() / "out";
  const fs::path kept = folder.path() / "kept";
  std::vector<std::string> arguments = {
      "run",       (bench::source_dir() / "examples" / "corridor.yaml").string(),
      "--outputs", "d64,summary",
      "--quiet",   "--out",
      out.string()};
  arguments.insert(arguments.end(), extent.begin(), extent.end());
  if (!time_processes(state, bench::owsim_program(), arguments, out)) return;
  // One more run, untimed, for summary.json: the loop time of a run like those timed.
  arguments[6] = kept.string();
  if (bench::run_child(bench::owsim_program(), arguments).exit_status != 0) return;
  const double loop_s = nlohmann::json::parse(std::ifstream(kept / "summary.json"))["wall_s"];
  state.counters["loop_s"] = loop_s;
  state.counters["process_vs_loop"] = state.counters["process_s"] / loop_s;
}

void BM_OneFrame(benchmark::State& state) { time_run(state, {"--frames", "1"}); }
void BM_Flight30s(benchmark::State& state) { time_run(state, {"--duration", "30"}); }

BENCHMARK(BM_PlainCpp)->Iterations(40)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Version)->Iterations(40)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OneFrame)->Iterations(20)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Flight30s)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace owsim
