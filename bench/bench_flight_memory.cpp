// Peak memory of a long flight (DESIGN.md "Flight pipeline": memory stays flat over hours of
// flight): `owsim run --outputs d64` over the scene of examples/corridor.yaml for 1 minute and for
// 30 minutes, each in its own process, its peak resident set read with wait4 (ru_maxrss).
// The scenario is corridor.yaml with its trajectory replaced by a racetrack flown 10 times: the
// scenario's own zig-zag across the lines (-1300,-250) → (-400,150) → (400,-150) → (1300,200),
// then back west along n = 800 north of the wood (1700,800) → (-1700,800) → (-1900,-300), 90 m
// up at 40 m/s (about 216 s a lap) — the same route for both durations, so only the length of
// the flight differs. Counters: peak_rss_mb, pulses_per_s, and for 30 minutes rss_vs_1min.
// The `owsim` run is OWSIM_CLI, else the build's own (../owsim beside this program's folder).
// Each run takes one iteration (the 30-minute one simulates 110 million pulses: minutes).
#include <benchmark/benchmark.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "child_process.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using bench::ChildRun;
using bench::owsim_program;
using bench::run_child;
using bench::ScratchFolder;
using bench::source_dir;

constexpr int kLaps = 10;
constexpr std::array<std::array<double, 2>, 7> kLap = {{{-1300, -250},
                                                        {-400, 150},
                                                        {400, -150},
                                                        {1300, 200},
                                                        {1700, 800},
                                                        {-1700, 800},
                                                        {-1900, -300}}};
constexpr double kHeightM = 90.0;
constexpr int kPulsesPerFrame = 128 * 159;  // SENSOR-SPEC §2
constexpr double kFrameS = kPulsesPerFrame / 61'111.0;

// corridor.yaml with the racetrack as its trajectory, written into `folder`.
fs::path write_loop_scenario(const fs::path& folder, double duration_s) {
  YAML::Node scenario = YAML::LoadFile((source_dir() / "examples" / "corridor.yaml").string());
  YAML::Node points(YAML::NodeType::Sequence);
  for (int lap = 0; lap < kLaps; ++lap) {
    for (const auto& [e, n] : kLap) {
      YAML::Node point;
      point["e"] = e;
      point["n"] = n;
      point["u"] = kHeightM;
      points.push_back(point);
    }
  }
  YAML::Node last;
  last["e"] = kLap[0][0];
  last["n"] = kLap[0][1];
  last["u"] = kHeightM;
  points.push_back(last);
  scenario["trajectory"]["waypoints"]["points"] = points;
  scenario["trajectory"]["duration_s"] = duration_s;
  const fs::path path = folder / "corridor_loop.yaml";
  std::ofstream(path) << scenario << '\n';
  return path;
}

double one_minute_peak_mb = 0.0;

// Arg: minutes of flight.
void BM_FlightPeakMemory(benchmark::State& state) {
  const double duration_s = 60.0 * static_cast<double>(state.range(0));
  const ScratchFolder folder;
  const fs::path scenario = write_loop_scenario(folder.path(), duration_s);
  const fs::path program = owsim_program();
  ChildRun run;
  for (auto _ : state) {
    run = run_child(program, {"run", scenario.string(), "--outputs", "d64", "--quiet", "--out",
                              (folder.path() / "out").string()});
    state.SetIterationTime(run.wall_s);
    std::error_code ignored;
    fs::remove_all(folder.path() / "out", ignored);
  }
  if (run.exit_status != 0) {
    state.SkipWithError("owsim run failed (run it by hand to see why)");
    return;
  }
  const double frames = std::floor(duration_s / kFrameS + 1e-9);
  state.counters["peak_rss_mb"] = run.peak_rss_mb;
  state.counters["pulses_per_s"] = frames * kPulsesPerFrame / run.wall_s;
  if (state.range(0) == 1) one_minute_peak_mb = run.peak_rss_mb;
  if (state.range(0) != 1 && one_minute_peak_mb > 0) {
    state.counters["rss_vs_1min"] = run.peak_rss_mb / one_minute_peak_mb;
  }
}
BENCHMARK(BM_FlightPeakMemory)
    ->Arg(1)
    ->Arg(30)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace owsim
