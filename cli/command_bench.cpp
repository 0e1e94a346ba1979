// owsim bench [SCENARIO] [--frames N] [--threads N] [--json] — throughput figures (INTERFACE.md
// `owsim bench --json`, DESIGN.md "Performance model"); the measuring is cli/throughput_bench.hpp.
#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/throughput_bench.hpp"
#include "io/files/json_text.hpp"

namespace owsim::cli {
namespace {

nlohmann::ordered_json to_json(const ThroughputReport& report) {
  return {{"scenario", report.scenario},
          {"frames", report.frames},
          {"pulses", report.pulses},
          {"threads", report.threads},
          {"end_to_end_pulses_per_s", report.end_to_end_pulses_per_s},
          {"trace_only_pulses_per_s", report.trace_only_pulses_per_s},
          {"traversal_only_pulses_per_s", report.traversal_only_pulses_per_s},
          {"traversal_share_paired", report.traversal_share_paired},
          {"end_to_end_over_trace_paired", report.end_to_end_over_trace_paired},
          {"brute_force_pulses_per_s", report.brute_force_pulses_per_s},
          {"single_thread_pulses_per_s", report.single_thread_pulses_per_s},
          {"traversal_share_single_thread_paired", report.traversal_share_single_thread_paired},
          {"end_to_end_over_trace_single_thread_paired",
           report.end_to_end_over_trace_single_thread_paired},
          {"las_pulses_per_s", report.las_pulses_per_s},
          {"points_pulses_per_s", report.points_pulses_per_s},
          {"truth_pulses_per_s", report.truth_pulses_per_s},
          {"truth_ratio_paired", report.truth_ratio_paired},
          {"detections_pulses_per_s", report.detections_pulses_per_s},
          {"detections_ratio_paired", report.detections_ratio_paired},
          {"detector_frames_per_s", report.detector_frames_per_s},
          {"detector_realtime_factor", report.detector_realtime_factor},
          {"noise_off_pulses_per_s", report.noise_off_pulses_per_s},
          {"realtime_factor", report.realtime_factor},
          {"trace_api", std::string(to_string(report.trace_api))},
          {"peak_rss_mb", report.peak_rss_mb},
          {"trace_api_pulses_per_s",
           {{"per_ray", report.trace_pulses_per_s[0]},
            {"stream", report.trace_pulses_per_s[1]},
            {"packet8", report.trace_pulses_per_s[2]},
            {"packet16", report.trace_pulses_per_s[3]}}},
          {"brute_force_subset_pulses", report.brute_force_pulses},
          {"repeats", report.repeats}};
}

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

void print_text(const ThroughputReport& r) {
  fmt::print("{}: {} frames, {} pulses, {} threads, best of {} rounds\n", r.scenario, r.frames,
             r.pulses, r.threads, r.repeats);
  fmt::print(
      "  end-to-end     {:>12.0f} pulses/s  {:6.2f}x real time ({:.0f} pulses/s), "
      "{:.2f} of trace-only ({:.2f} paired by round, median)\n",
      r.end_to_end_pulses_per_s, r.realtime_factor, r.prf_hz,
      ratio(r.end_to_end_pulses_per_s, r.trace_only_pulses_per_s),
      r.end_to_end_over_trace_paired);
  fmt::print(
      "  trace-only     {:>12.0f} pulses/s  {} won (per_ray {:.0f}, stream {:.0f}, "
      "packet8 {:.0f}, packet16 {:.0f})\n",
      r.trace_only_pulses_per_s, to_string(r.trace_api), r.trace_pulses_per_s[0],
      r.trace_pulses_per_s[1], r.trace_pulses_per_s[2], r.trace_pulses_per_s[3]);
  fmt::print(
      "  traversal-only {:>12.0f} pulses/s  Embree's traversal alone (callbacks reduced to "
      "recording the hit): {:.2f} of end-to-end's time, paired by round (median)\n",
      r.traversal_only_pulses_per_s, r.traversal_share_paired);
  fmt::print(
      "  single thread  {:>12.0f} pulses/s  end-to-end on {} threads is {:.2f}x; on one thread, "
      "traversal-only {:.2f} and trace-only {:.2f} of its time (paired by round, median)\n",
      r.single_thread_pulses_per_s, r.threads,
      ratio(r.end_to_end_pulses_per_s, r.single_thread_pulses_per_s),
      r.traversal_share_single_thread_paired, r.end_to_end_over_trace_single_thread_paired);
  fmt::print("  points.las     {:>12.0f} pulses/s  {:.2f} of end-to-end (--outputs las)\n",
             r.las_pulses_per_s, ratio(r.las_pulses_per_s, r.end_to_end_pulses_per_s));
  fmt::print("  all points     {:>12.0f} pulses/s  {:.2f} of end-to-end (--outputs points)\n",
             r.points_pulses_per_s, ratio(r.points_pulses_per_s, r.end_to_end_pulses_per_s));
  fmt::print(
      "  words + truth  {:>12.0f} pulses/s  {:.2f} of end-to-end (--outputs d64,truth); {:.3f} "
      "paired by round (median)\n",
      r.truth_pulses_per_s, ratio(r.truth_pulses_per_s, r.end_to_end_pulses_per_s),
      r.truth_ratio_paired);
  fmt::print(
      "  detections     {:>12.0f} pulses/s  {:.2f} of end-to-end (--outputs d64,detections); {:.3f} "
      "paired by round (median)\n",
      r.detections_pulses_per_s, ratio(r.detections_pulses_per_s, r.end_to_end_pulses_per_s),
      r.detections_ratio_paired);
  fmt::print("  detector       {:>12.1f} frames/s  on one thread: {:.0f}x real time\n",
             r.detector_frames_per_s, r.detector_realtime_factor);
  fmt::print(
      "  noise off      {:>12.0f} pulses/s  end-to-end with the receiver's noise is {:.2f} of it "
      "(sensor.receiver.noise: off)\n",
      r.noise_off_pulses_per_s, ratio(r.end_to_end_pulses_per_s, r.noise_off_pulses_per_s));
  fmt::print("  brute force    {:>12.0f} pulses/s  ({} pulses traced), BVH trace is {:.0f}x\n",
             r.brute_force_pulses_per_s, r.brute_force_pulses,
             ratio(r.trace_only_pulses_per_s, r.brute_force_pulses_per_s));
  fmt::print("  peak memory    {:>12.1f} MiB\n", r.peak_rss_mb);
}

}  // namespace

void add_bench_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<ThroughputOptions>();
  auto json = std::make_shared<bool>(false);
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand("bench",
                                         "throughput figures: end-to-end, trace-only, "
                                         "brute force, one thread");
  command
      ->add_option("scenario", options->scenario,
                   "scenario file (YAML); default examples/corridor.yaml")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  command->add_option("--frames", options->frames, "frames 0..N-1 of the scenario are measured")
      ->check(positive_number())
      ->capture_default_str();
  command->add_option("--threads", options->threads, "worker threads (default: every core)")
      ->check(positive_number());
  command->add_option("--repeats", options->repeats, "rounds; each figure is the best round")
      ->check(positive_number())
      ->capture_default_str();
  command
      ->add_option("--brute-force-pulses", options->brute_force_pulses,
                   "pulses the brute-force tracer traces (spread over the frames)")
      ->check(positive_number())
      ->capture_default_str();
  command->add_flag("--json", *json, "print the figures as JSON");
  command->add_flag("--quiet", *quiet, "no progress line");
  command->footer(
      "Every figure is pulses per second of wall time over all pulses of the frames, measured "
      "in this one run on the same frames. end-to-end writes the sensor words (and nothing "
      "else) into a temporary folder; trace-only traces the same rays with Embree alone, in "
      "each query form; traversal-only the same rays through the same BVHs with the callbacks "
      "reduced to recording the hit (Embree's own part of a pulse); single thread is end-to-end on "
      "one thread, each round paired with trace-only and traversal-only on one thread; brute "
      "force traces a subset "
      "without the BVH and is scaled to the whole frames.");
  command->callback([options, json, quiet] {
    options->progress = !*quiet;
    const ThroughputReport report = measure_throughput(*options);
    if (*json) {
      fmt::print("{}\n", json_text(to_json(report), 2));
    } else {
      print_text(report);
    }
  });
}

}  // namespace owsim::cli
