#pragma once
// `owsim run` as a function: scenario → scene, trajectory, Embree scene → the frame pipeline →
// the outputs. The command only parses options into RunOptions and prints; the bench command and
// the end-to-end tests call the same function.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>

#include "engine/frame_tracer.hpp"
#include "io/flight_outputs.hpp"

namespace owsim::cli {

struct RunOptions {
  std::filesystem::path scenario;
  std::optional<std::filesystem::path> out;  // default out/<scenario name>/
  std::optional<std::int64_t> frames;
  std::optional<double> duration_s;
  int threads = 0;                          // 0 = every core
  std::optional<std::uint64_t> seed;
  std::set<OutputKind> outputs = all_outputs();
  bool no_noise = false;
  bool progress = false;  // a progress line on stderr
  TraceApi trace_api = TraceApi::stream;
};

struct RunReport {
  std::filesystem::path directory;
  std::int64_t frames = 0;
  std::uint64_t pulses = 0;
  double wall_s = 0.0;
  double pulses_per_s = 0.0;
  double realtime_factor = 0.0;
  int threads = 0;
};

RunReport run_flight_scenario(const RunOptions& options);

}  // namespace owsim::cli
