#include "cli/throughput_bench.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <vector>

#include "cli/peak_memory.hpp"
#include "engine/brute_force_tracer.hpp"
#include "geometry/error.hpp"
#include "io/detections/flight_detections.hpp"
#include "owsim/flight_run.hpp"
#include "owsim/simulation.hpp"

namespace owsim::cli {
namespace {

using Clock = std::chrono::steady_clock;

template <typename Work>
double seconds_of(Work&& work) {
  const auto start = Clock::now();
  work();
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A fresh folder under the system's temporary directory, removed with its contents at the end.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "owsim_bench_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw Error(pattern + ": cannot create a temporary folder for the word file");
    }
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// One frame's rays as the tracer takes them, built once before any timing.
struct FrameRays {
  std::vector<PulseRay> rays;
  std::vector<std::uint8_t> active;
};

std::vector<FrameRays> build_frame_rays(const FlightSetup& setup, std::int64_t frames) {
  std::vector<FrameRays> out(static_cast<std::size_t>(frames));
  FrameResult scratch;
  for (std::int64_t f = 0; f < frames; ++f) {
    setup.simulator.build_rays(f, setup.trajectory, scratch);
    out[static_cast<std::size_t>(f)] = FrameRays{scratch.rays, scratch.active};
  }
  return out;
}

// Every frame's rays through `tracer`, one frame after the other (each frame in parallel chunks).
double trace_seconds(const FrameTracer& tracer, const std::vector<FrameRays>& frames,
                     std::vector<PulseCandidates>& candidates) {
  return seconds_of([&] {
    for (const FrameRays& frame : frames) tracer.trace(frame.rays, frame.active, candidates);
  });
}

// About `wanted` active pulses spread evenly over all frames (every stride-th active pulse).
std::vector<const PulseRay*> brute_force_subset(const std::vector<FrameRays>& frames,
                                                std::int64_t wanted, std::uint64_t& active_total) {
  active_total = 0;
  for (const FrameRays& frame : frames) {
    active_total +=
        static_cast<std::uint64_t>(std::count(frame.active.begin(), frame.active.end(), 1));
  }
  const std::uint64_t stride = std::max<std::uint64_t>(
      1, active_total / static_cast<std::uint64_t>(std::max<std::int64_t>(1, wanted)));
  std::vector<const PulseRay*> subset;
  std::uint64_t index = 0;
  for (const FrameRays& frame : frames) {
    for (std::size_t k = 0; k < frame.rays.size(); ++k) {
      if (frame.active[k] == 0) continue;
      if (index++ % stride == 0) subset.push_back(&frame.rays[k]);
    }
  }
  return subset;
}

// The subset through the brute-force tracer, in parallel on the current arena.
double brute_force_seconds(const BruteForceTracer& tracer,
                           const std::vector<const PulseRay*>& subset) {
  return seconds_of([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, subset.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        PulseCandidates candidates;
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                          tracer.trace(*subset[i], candidates);
                        }
                      });
  });
}

// What `owsim run --outputs <kinds>` does over the frames (d64 by default), into a scratch folder.
// Timed like `owsim run`'s wall_s: the frame pipeline with every byte written to the files'
// buffers, not the final commit (flush, fsync, rename) that follows it.
double end_to_end_seconds(const FrameSimulator& simulator, const FlightSetup& setup, int threads,
                          const std::set<OutputKind>& kinds = {OutputKind::d64}) {
  const ScratchFolder folder;
  FlightOutputs outputs(flight_output_options(setup, folder.path(), kinds), setup.scene,
                        setup.scenario.scan, setup.local_frame);
  const double seconds = seconds_of([&] {
    simulate_frames(simulator, setup, FlightRange{0, setup.frames}, threads, outputs);
  });
  outputs.finish({});
  return seconds;
}

// `owsim run --outputs d64,detections` over the frames, as end_to_end_seconds; `detector_s` is
// told the seconds the detector itself took (on the pipeline's one serial thread).
double detections_seconds(const FrameSimulator& simulator, const FlightSetup& setup, int threads,
                          double& detector_s) {
  const ScratchFolder folder;
  FlightOutputs outputs(
      flight_output_options(setup, folder.path(), {OutputKind::d64, OutputKind::detections}),
      setup.scene, setup.scenario.scan, setup.local_frame);
  FlightDetections detections(setup.scenario, setup.trajectory, folder.path() / "detections.csv");
  const double seconds = seconds_of([&] {
    simulate_frames(simulator, setup, FlightRange{0, setup.frames}, threads, outputs, {},
                    &detections);
  });
  outputs.finish({});
  detections.finish();
  detector_s = detections.report().detector_s;
  return seconds;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

class RoundProgress {
 public:
  explicit RoundProgress(bool enabled) : enabled_(enabled && ::isatty(STDERR_FILENO) != 0) {}
  void note(const char* what, int round, int rounds, double pulses_per_s) const {
    if (!enabled_) return;
    std::fprintf(stderr, "\r%-28s round %d/%d  %.3f Mpulses/s      ", what, round, rounds,
                 pulses_per_s / 1e6);
  }
  void done() const {
    if (enabled_) std::fprintf(stderr, "\r%70s\r", "");
  }

 private:
  bool enabled_;
};

}  // namespace

ThroughputReport measure_throughput(const ThroughputOptions& options) {
  if (options.frames < 1) throw input_error("--frames", "must be at least 1");
  if (options.repeats < 1) throw input_error("--repeats", "must be at least 1");
  if (options.brute_force_pulses < 1)
    throw input_error("--brute-force-pulses", "must be at least 1");
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));

  SimulationOptions run;
  run.frames = options.frames;
  run.threads = threads;
  const Simulation simulation = Simulation::open(options.scenario, run);
  const FlightSetup& setup = simulation.setup();
  const ScanParams& scan = setup.scenario.scan;
  const std::uint64_t pulses = static_cast<std::uint64_t>(setup.frames) *
                               static_cast<std::uint64_t>(scan.pulses_per_frame());
  const auto rate = [&](double seconds) {
    return seconds > 0 ? static_cast<double>(pulses) / seconds : 0.0;
  };
  const RoundProgress progress(options.progress);

  const std::vector<FrameRays> frames = build_frame_rays(setup, setup.frames);
  std::vector<PulseCandidates> candidates(static_cast<std::size_t>(scan.pulses_per_frame()));

  // Trace-only, each query form, interleaved over the rounds; the fastest form wins.
  constexpr double kNever = std::numeric_limits<double>::infinity();
  std::array<double, kTraceApis.size()> trace_best;
  trace_best.fill(kNever);
  for (int round = 1; round <= options.repeats; ++round) {
    for (std::size_t a = 0; a < kTraceApis.size(); ++a) {
      const FrameTracer tracer(setup.embree_scene, kTraceApis[a]);
      trace_best[a] = std::min(trace_best[a], trace_seconds(tracer, frames, candidates));
      progress.note(to_string(kTraceApis[a]).data(), round, options.repeats, rate(trace_best[a]));
    }
  }
  const auto winner = static_cast<std::size_t>(
      std::min_element(trace_best.begin(), trace_best.end()) - trace_best.begin());
  const TraceApi api = kTraceApis[winner];
  const FrameTracer tracer(setup.embree_scene, api);
  const FrameTracer traversal(setup.embree_scene, api, {}, TraceWork::traversal_only);
  const FrameSimulator simulator(setup.simulator.params(), setup.embree_scene, api);
  FrameSimulatorParams deterministic = setup.simulator.params();
  deterministic.receiver.noise.on = false;
  const FrameSimulator noise_off(deterministic, setup.embree_scene, api);

  // End-to-end on every thread and on one, interleaved with trace-only of the winning form.
  double end_to_end_best = kNever;
  double single_thread_best = kNever;
  double las_best = kNever;
  double points_best = kNever;
  double truth_best = kNever;
  double noise_off_best = kNever;
  double traversal_best = kNever;
  std::vector<double> traversal_shares;  // per round: traversal-only's seconds over end-to-end's
  std::vector<double> trace_shares;      // per round: trace-only's seconds over end-to-end's
  std::vector<double> truth_ratios;      // per round: the words' seconds over words + truth's
  double detections_best = kNever;
  double detector_best = kNever;           // the detector's own seconds, its best round
  std::vector<double> detections_ratios;   // per round: the words' seconds over words + detections'
  std::vector<double> traversal_shares_1;  // the same two on one thread
  std::vector<double> trace_shares_1;
  tbb::task_arena one_thread(1);
  for (int round = 1; round <= options.repeats; ++round) {
    const double trace_s = trace_seconds(tracer, frames, candidates);
    trace_best[winner] = std::min(trace_best[winner], trace_s);
    const double traversal_s = trace_seconds(traversal, frames, candidates);
    traversal_best = std::min(traversal_best, traversal_s);
    progress.note("traversal-only", round, options.repeats, rate(traversal_best));
    // The words alone and the words with truth.csv back to back, in turn first, so that their
    // ratio compares runs made under the same conditions (and the same round's noise).
    double words_s = 0.0, truth_s = 0.0;
    const auto words = [&] {
      words_s = end_to_end_seconds(simulator, setup, threads);
      end_to_end_best = std::min(end_to_end_best, words_s);
      progress.note("end-to-end", round, options.repeats, rate(end_to_end_best));
    };
    const auto words_and_truth = [&] {
      truth_s = end_to_end_seconds(simulator, setup, threads, {OutputKind::d64, OutputKind::truth});
      truth_best = std::min(truth_best, truth_s);
      progress.note("words and truth", round, options.repeats, rate(truth_best));
    };
    if (round % 2 == 1) {
      words();
      words_and_truth();
    } else {
      words_and_truth();
      words();
    }
    truth_ratios.push_back(truth_s > 0.0 ? words_s / truth_s : 0.0);
    // The detector in the loop, right after the words alone (the pair's ratio as truth's).
    double detector_s = 0.0;
    const double detections_s = detections_seconds(simulator, setup, threads, detector_s);
    detections_best = std::min(detections_best, detections_s);
    detector_best = std::min(detector_best, detector_s);
    detections_ratios.push_back(detections_s > 0.0 ? words_s / detections_s : 0.0);
    progress.note("words and detections", round, options.repeats, rate(detections_best));
    traversal_shares.push_back(words_s > 0.0 ? traversal_s / words_s : 0.0);
    trace_shares.push_back(words_s > 0.0 ? trace_s / words_s : 0.0);
    const double trace_1_s =
        one_thread.execute([&] { return trace_seconds(tracer, frames, candidates); });
    const double traversal_1_s =
        one_thread.execute([&] { return trace_seconds(traversal, frames, candidates); });
    const double single_s =
        one_thread.execute([&] { return end_to_end_seconds(simulator, setup, 1); });
    single_thread_best = std::min(single_thread_best, single_s);
    traversal_shares_1.push_back(single_s > 0.0 ? traversal_1_s / single_s : 0.0);
    trace_shares_1.push_back(single_s > 0.0 ? trace_1_s / single_s : 0.0);
    progress.note("single thread", round, options.repeats, rate(single_thread_best));
    noise_off_best = std::min(noise_off_best, end_to_end_seconds(noise_off, setup, threads));
    progress.note("receiver noise off", round, options.repeats, rate(noise_off_best));
    las_best = std::min(las_best, end_to_end_seconds(simulator, setup, threads, {OutputKind::las}));
    progress.note("points.las", round, options.repeats, rate(las_best));
    points_best = std::min(
        points_best, end_to_end_seconds(simulator, setup, threads, parse_output_list("points")));
    progress.note("points", round, options.repeats, rate(points_best));
  }

  // Brute force on a subset, scaled to every active pulse of the frames.
  std::uint64_t active_total = 0;
  const std::vector<const PulseRay*> subset =
      brute_force_subset(frames, options.brute_force_pulses, active_total);
  const BruteForceTracer brute_force(setup.scene, setup.embree_scene.terrain_mesh(),
                                     setup.scenario.receiver);
  const double subset_seconds = brute_force_seconds(brute_force, subset);
  const double brute_force_all_s =
      subset_seconds * static_cast<double>(active_total) / static_cast<double>(subset.size());
  progress.done();

  ThroughputReport report;
  report.scenario = setup.scenario.name;
  report.frames = setup.frames;
  report.pulses = pulses;
  report.threads = threads;
  report.end_to_end_pulses_per_s = rate(end_to_end_best);
  report.trace_only_pulses_per_s = rate(trace_best[winner]);
  report.brute_force_pulses_per_s = rate(brute_force_all_s);
  report.single_thread_pulses_per_s = rate(single_thread_best);
  report.las_pulses_per_s = rate(las_best);
  report.points_pulses_per_s = rate(points_best);
  report.truth_pulses_per_s = rate(truth_best);
  report.noise_off_pulses_per_s = rate(noise_off_best);
  report.truth_ratio_paired = median(truth_ratios);
  report.detections_pulses_per_s = rate(detections_best);
  report.detections_ratio_paired = median(detections_ratios);
  report.detector_frames_per_s =
      detector_best > 0.0 ? static_cast<double>(setup.frames) / detector_best : 0.0;
  report.detector_realtime_factor = report.detector_frames_per_s * scan.frame_duration_s();
  report.traversal_only_pulses_per_s = rate(traversal_best);
  report.traversal_share_paired = median(traversal_shares);
  report.end_to_end_over_trace_paired = median(trace_shares);
  report.traversal_share_single_thread_paired = median(traversal_shares_1);
  report.end_to_end_over_trace_single_thread_paired = median(trace_shares_1);
  report.realtime_factor = report.end_to_end_pulses_per_s / scan.prf_hz;
  report.trace_api = api;
  report.peak_rss_mb = peak_rss_mb();
  report.brute_force_pulses = subset.size();
  for (std::size_t a = 0; a < kTraceApis.size(); ++a) {
    report.trace_pulses_per_s[a] = rate(trace_best[a]);
  }
  report.repeats = options.repeats;
  report.prf_hz = scan.prf_hz;
  return report;
}

}  // namespace owsim::cli
