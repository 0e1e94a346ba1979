#pragma once
// Everything `owsim run` writes (INTERFACE.md "owsim run outputs"), fed one frame at a time in
// frame order: the sensor words (flight.d64 or flight.hellas), points.csv / points.las /
// points.ply, trajectory.csv, summary.json and quicklook/. Each file is written under a temporary
// name and appears under its final name only when finish() completes it, so an interrupted run
// leaves nothing half-written.
//
// Given a run fingerprint, FlightOutputs also keeps the folder's checkpoint
// (io/run/run_checkpoint.hpp) between frames, at most every checkpoint_interval_s of wall time: a
// killed run (SIGKILL, no destructor) leaves its temporaries and the checkpoint, and FlightOutputs
// built from that checkpoint cuts the temporaries back to it and continues them, so the finished
// files are byte for byte those of an uninterrupted run, wherever the checkpoints fell.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/points/point_record.hpp"
#include "io/run/flight_summary.hpp"
#include "io/run/frame_encoding.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

enum class OutputKind { d64, points, trajectory, summary, quicklook };

// "d64,summary" → {d64, summary}; the word file is flight.hellas for a HELLAS scenario. Throws
// owsim::Error naming the unknown item.
[[nodiscard]] std::set<OutputKind> parse_output_list(std::string_view list);
[[nodiscard]] std::set<OutputKind> all_outputs();

struct FlightOutputOptions {
  std::filesystem::path directory;
  std::set<OutputKind> outputs = all_outputs();
  int quicklook_every_nth_frame = 10;
  Eigen::AlignedBox2d map_region;  // the quick-look map's extent (east, north)
  // The run's fingerprint (RunCheckpoint::run, an object): checkpoints are kept. Null: none.
  nlohmann::json checkpoint_run;
  double checkpoint_interval_s = 0.5;
};

class WordSink;
class PointsCsvWriter;
class LasWriter;
class PlyWriter;
class TrajectoryCsvWriter;
class Quicklook;
struct RunCheckpoint;

class FlightOutputs {
 public:
  // Creates the directory and opens every requested output (as temporaries); with checkpoints on,
  // first removes a checkpoint left in the folder. With `resume_from` (the folder's checkpoint,
  // of the same run: the caller has compared its fingerprint), continues the outputs from it
  // instead: frames_done() is then its frame count. Throws owsim::Error if a temporary it names is
  // missing or shorter, or its state does not fit the outputs.
  FlightOutputs(const FlightOutputOptions& options, const Scene& scene, const ScanParams& scan,
                const LocalFrame& local_frame, const RunCheckpoint* resume_from = nullptr);
  // Without finish() (an exception): the temporaries go, and the checkpoint with them.
  ~FlightOutputs();
  FlightOutputs(const FlightOutputs&) = delete;
  FlightOutputs& operator=(const FlightOutputs&) = delete;

  // One frame, in order from frames_done(); `frame_start` is the aircraft's pose at the frame's
  // first pulse. Writes a checkpoint afterwards if one is due. encode_frame then add_frame.
  void add_frame(const FrameView& frame, const Pose& frame_start);

  // The same in two steps, so the costly part can run on the pipeline's parallel stage:
  // encode_frame() fills `out` with the frame's bytes for every output (any frame, any order, on
  // any thread, concurrently with itself and with add_frame(); each call needs its own `out`;
  // an error is kept in `out`, not thrown). add_frame() appends them: frames in order from
  // frames_done(), each with its own encoding; throws what encoding met, or owsim::Error if
  // `encoded` is not of `frame`.
  void encode_frame(const FrameView& frame, const Pose& frame_start, FrameEncoding& out) const;
  void add_frame(const FrameView& frame, const FrameEncoding& encoded);

  // encode_frame() in three steps, so the per-pulse part (the words and the summary tally) runs on
  // each block of a frame while the simulation has it in cache (FrameBlockDone of
  // engine/frame_simulator.hpp): size_encoding() sizes an encoding's buffers for this scan, once;
  // encode_pulses() encodes pulses [begin, end) of the frame, whole lines, concurrently for
  // disjoint blocks of the frame (every line in exactly one block), an error kept in `out`; after
  // the frame's last block, finish_encoding() does the rest. The result is encode_frame()'s.
  // encode_pulses throws owsim::Error if the pulses are not whole lines of a frame of this scan or
  // `out` is not sized.
  void size_encoding(FrameEncoding& out) const;
  void encode_pulses(const FrameView& frame, int begin, int end, FrameEncoding& out) const;
  void finish_encoding(const FrameView& frame, const Pose& frame_start, FrameEncoding& out) const;

  // Completes every file and writes summary.json with `run_facts` merged into the totals; then
  // removes the checkpoint.
  void finish(const nlohmann::json& run_facts);

  // Tallies returns only when summary.json is among the outputs (frames are always counted).
  [[nodiscard]] const FlightSummary& summary() const { return summary_; }
  // The frames in the outputs: the next frame add_frame() takes.
  [[nodiscard]] std::int64_t frames_done() const { return frames_done_; }

 private:
  using Clock = std::chrono::steady_clock;

  [[nodiscard]] bool wants(OutputKind kind) const { return options_.outputs.contains(kind); }
  [[nodiscard]] bool checkpointing() const { return !options_.checkpoint_run.is_null(); }
  void open_outputs(const Scene& scene, const RunCheckpoint* resume_from);
  void write_checkpoint(bool finishing);

  FlightOutputOptions options_;
  ScanParams scan_;
  const LocalFrame* local_frame_;
  FlightSummary summary_;
  std::unique_ptr<WordSink> words_;
  std::unique_ptr<PointsCsvWriter> points_csv_;
  std::unique_ptr<LasWriter> points_las_;
  std::unique_ptr<PlyWriter> points_ply_;
  std::unique_ptr<TrajectoryCsvWriter> trajectory_;
  std::unique_ptr<Quicklook> quicklook_;
  FrameEncoding encoding_;  // add_frame(frame, frame_start)'s, reused per frame
  std::int64_t frames_done_ = 0;
  bool resumed_while_finishing_ = false;  // the checkpoint already describes the finished frames
  bool checkpoint_on_disk_ = false;        // this run wrote one, or resumed from one
  bool finished_ = false;
  std::filesystem::path checkpoint_path_;
  Clock::time_point last_checkpoint_;
};

}  // namespace owsim
