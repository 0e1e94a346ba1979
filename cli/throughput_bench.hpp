#pragma once
// `owsim bench` as a function (DESIGN.md "Performance model", INTERFACE.md `owsim bench --json`):
// the throughput figures of one scenario, all measured in one process on the same frames —
// frames 0..N−1, the frames `owsim run SCENARIO --frames N` simulates.
//   trace_only   — the frames' rays built once, then FrameTracer::trace alone over them, for each
//                  Embree query form (per ray, stream, packets of 8); the fastest form wins;
//   traversal_only — the same rays through the same BVHs in the winning form with the callbacks
//                  reduced to recording the hit (TraceWork::traversal_only): Embree's own part;
//                  its share of end-to-end's time is the physical limit's measure;
//   end_to_end   — everything `owsim run` does with the winning form (pattern, poses, rays,
//                  trace, receiver, word packing) writing flight.d64 / flight.hellas into a
//                  temporary folder, the other outputs off (as on a long flight, --outputs d64);
//   single_thread — the same end-to-end run in a TBB arena of one thread, paired by round with
//                  trace-only and traversal-only in the same arena;
//   detections   — the same end-to-end run with the reference obstacle detector in the loop
//                  (--outputs d64,detections), paired by round with the words alone; and the
//                  detector's own frames per second on the one thread it runs on (its time inside
//                  ObstacleDetector::add_frame over the frames), and that over the sensor's frame
//                  rate: how many times real time the detector keeps up on one core;
//   las, points  — the same end-to-end run writing points.las alone (--outputs las), and the three
//                  point files (--outputs points), instead of the words;
//   brute_force  — the source's method (every ray against every segment, cylinder and triangle)
//                  on an evenly spread subset of the frames' pulses, on the same threads,
//                  scaled to the whole frames.
// Every figure counts all pulses of the frames (the reference fiber's too) per second of wall
// time. Each timed figure is the best of `repeats` rounds (the rounds interleave the figures, so
// a burst of load on a shared machine hits one round of each, and the best round is the one least
// disturbed). peak_rss_mb is the process's peak resident set (getrusage), the stored rays
// included.
#include <cstdint>
#include <filesystem>
#include <string>

#include "engine/frame_tracer.hpp"

namespace owsim::cli {

struct ThroughputOptions {
  std::filesystem::path scenario = "examples/corridor.yaml";
  std::int64_t frames = 30;
  int threads = 0;                         // 0 = every core
  int repeats = 3;                         // rounds; each figure is the best round
  std::int64_t brute_force_pulses = 2048;  // the subset the brute-force tracer traces
  bool progress = false;                   // a line per round on stderr
};

struct ThroughputReport {
  std::string scenario;
  std::int64_t frames = 0;
  std::uint64_t pulses = 0;  // frames × pulses per frame
  int threads = 0;
  double end_to_end_pulses_per_s = 0.0;
  double trace_only_pulses_per_s = 0.0;
  double brute_force_pulses_per_s = 0.0;
  double single_thread_pulses_per_s = 0.0;
  double las_pulses_per_s = 0.0;     // --outputs las
  double points_pulses_per_s = 0.0;  // --outputs points (csv, las, ply)
  double truth_pulses_per_s = 0.0;   // --outputs d64,truth: the words with the ground truth
  // End-to-end with sensor.receiver.noise off (SENSOR-SPEC §11's statistics' cost is end-to-end
  // over this): the deterministic receiver of §7 on the same scene.
  double noise_off_pulses_per_s = 0.0;
  double realtime_factor = 0.0;  // end_to_end / the sensor's PRF
  double detections_pulses_per_s = 0.0;  // --outputs d64,detections
  // The words' seconds over the words with detections.csv's, each round's pair, the median.
  double detections_ratio_paired = 0.0;
  double detector_frames_per_s = 0.0;     // the detector alone, on its one thread (best round)
  double detector_realtime_factor = 0.0;  // detector_frames_per_s × the frame's duration
  TraceApi trace_api = TraceApi::stream;
  double peak_rss_mb = 0.0;
  // Not in INTERFACE.md's list, reported beside it:
  std::uint64_t brute_force_pulses = 0;      // the subset actually traced
  double trace_pulses_per_s[4] = {0, 0, 0, 0};  // by TraceApi (per_ray, stream, packet8, 16)
  int repeats = 0;
  double prf_hz = 0.0;
  // truth_pulses_per_s over end_to_end_pulses_per_s as each round's two back-to-back runs give
  // it, the median over the rounds: the cost of truth.csv with the machine's slow drifts (which
  // move the two best rounds apart) paired out.
  double truth_ratio_paired = 0.0;
  double traversal_only_pulses_per_s = 0.0;
  // Traversal-only's seconds over end-to-end's (on every thread), each round's pair, the median:
  // the share of a run that is Embree's traversal.
  double traversal_share_paired = 0.0;
  // Trace-only's seconds over end-to-end's (on every thread), each round's pair, the median: the
  // end-to-end-over-trace-only figure with the machine's drift between rounds paired out.
  double end_to_end_over_trace_paired = 0.0;
  // The same two pairs on one thread (a TBB arena of one): traversal-only's and trace-only's
  // seconds over single_thread's end-to-end, each round's, the median — the share of a one-thread
  // run that is Embree's traversal, and end-to-end over trace-only without the second core.
  double traversal_share_single_thread_paired = 0.0;
  double end_to_end_over_trace_single_thread_paired = 0.0;
};

[[nodiscard]] ThroughputReport measure_throughput(const ThroughputOptions& options);

}  // namespace owsim::cli
