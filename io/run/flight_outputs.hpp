#pragma once
// Everything `owsim run` writes (INTERFACE.md "owsim run outputs"), fed one frame at a time in
// frame order: the sensor words (flight.d64 or flight.hellas), points.csv / points.las /
// points.ply, trajectory.csv, summary.json, truth.csv, quicklook/ and flight.mcap. Each file is
// written under a temporary name and appears under its final name only when finish() completes it,
// so an interrupted run leaves nothing half-written.
//
// Given a run fingerprint, FlightOutputs also keeps the folder's checkpoint
// (io/run/run_checkpoint.hpp) between frames, at most every checkpoint_interval_s of wall time: a
// killed run (SIGKILL, no destructor) leaves its temporaries and the checkpoint, and FlightOutputs
// built from that checkpoint cuts the temporaries back to it and continues them, so the finished
// files are byte for byte those of an uninterrupted run, wherever the checkpoints fell. flight.mcap
// is not continued: a resume of a run with it is refused.
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
#include "io/run/frame_encoder.hpp"
#include "io/run/frame_encoding.hpp"
#include "io/run/output_kind.hpp"
#include "io/scenario/scenario_as_flown.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

struct FlightOutputOptions {
  std::filesystem::path directory;
  std::set<OutputKind> outputs = all_outputs();
  int quicklook_every_nth_frame = 10;
  Eigen::AlignedBox2d map_region;  // the quick-look map's extent (east, north)
  // The run's fingerprint (RunCheckpoint::run, an object): checkpoints are kept. Null: none.
  nlohmann::json checkpoint_run;
  double checkpoint_interval_s = 0.5;
  // What computes each frame's truth.csv rows (evaluation/frame_truth.hpp); must outlive the
  // outputs. Null: truth.csv is not written even if asked for.
  const FrameTruthSource* truth = nullptr;
  // The sensor's mount: flight.mcap's /tf_static (base_link → owsim_sensor).
  Mount sensor_mount;
  // scenario.yaml, the scenario as flown (io/scenario/scenario_as_flown.hpp), and the copies of
  // the files it names: written by finish() when the text is not empty.
  FlownScenario scenario;
};

class WordSink;
class PointsCsvWriter;
class LasWriter;
class PlyWriter;
class TrajectoryCsvWriter;
class TruthCsvWriter;
class Quicklook;
class FlightMcapFile;
struct RunCheckpoint;

class FlightOutputs {
 public:
  // Creates the directory and opens every requested output (as temporaries); with checkpoints on,
  // first removes a checkpoint left in the folder. With `resume_from` (the folder's checkpoint,
  // of the same run: the caller has compared its fingerprint), continues the outputs from it
  // instead: frames_done() is then its frame count. Throws owsim::Error if a temporary it names is
  // missing or shorter, or its state does not fit the outputs. `scene` and `local_frame` must
  // outlive the outputs.
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

  // encode_frame() in three steps (io/run/frame_encoder.hpp).
  void size_encoding(FrameEncoding& out) const { encoder_.size_encoding(out); }
  void encode_pulses(const FrameView& block, int begin, FrameEncoding& out) const {
    encoder_.encode_pulses(block, begin, out);
  }
  void finish_encoding(const FrameView& frame, const Pose& frame_start, FrameEncoding& out) const {
    encoder_.finish_encoding(frame, frame_start, out);
  }
  [[nodiscard]] const FrameEncoder& encoder() const { return encoder_; }
  // Whether add_frame(frame, encoded) and finish_encoding() read the frame's per-pulse records
  // (points, the quicklook): otherwise a frame given to them need hold only its index and sweep.
  [[nodiscard]] bool reads_frame_records() const {
    return encoder_.reads_frame_records() || quicklook_ != nullptr;
  }

  // A distributed run (distributed/): the bytes of a frame were written into the temporaries at
  // their places by the process that encoded it; this adds the rest in frame order from
  // frames_done() (the summary, the trajectory, the counts, the LAS statistics, truth.csv's rows,
  // flight.mcap's chunk) and counts the bytes as written. Writes no checkpoint: write_checkpoint()
  // does, once every process's bytes are in the files. Throws owsim::Error for a frame out of
  // order or without its flight.mcap chunk when flight.mcap is written.
  void add_placed_frame(const PlacedFrame& frame);
  // ORs the hits of the frames another Quicklook took (its QuicklookCheckpoint::map_mask) into
  // the map: a distributed run's processes each draw the hits and range images of their frames.
  void add_map_hits(std::span<const std::uint8_t> map_mask);
  // True when checkpoints are kept and checkpoint_interval_s has passed since the last one.
  [[nodiscard]] bool checkpoint_due() const;
  // Writes the checkpoint of the frames so far (hands every byte written to the kernel first).
  void write_checkpoint() { write_checkpoint(false); }
  // The temporaries the bytes of the outputs go to, by output (empty paths for outputs not
  // written), and the bytes each holds so far: where a distributed run places its frames.
  struct PlacedFile {
    std::filesystem::path partial_path;
    std::uint64_t bytes = 0;
  };
  struct PlacedFiles {
    PlacedFile words, csv, las, ply;
  };
  // Hands everything written so far to the kernel first.
  [[nodiscard]] PlacedFiles placed_files();

  // Completes every file and writes summary.json with `run_facts` merged into the totals; then
  // removes the checkpoint.
  void finish(const nlohmann::json& run_facts);

  // Tallies returns and keeps per-object state only when summary.json is among the outputs
  // (frames are always counted).
  [[nodiscard]] const FlightSummary& summary() const { return summary_; }
  // The frames in the outputs: the next frame add_frame() takes.
  [[nodiscard]] std::int64_t frames_done() const { return frames_done_; }

 private:
  using Clock = std::chrono::steady_clock;

  [[nodiscard]] bool wants(OutputKind kind) const { return encoder_.wants(kind); }
  [[nodiscard]] bool checkpointing() const { return !options_.checkpoint_run.is_null(); }
  void open_outputs(const Scene& scene, const RunCheckpoint* resume_from);
  void write_checkpoint(bool finishing);

  FlightOutputOptions options_;
  ScanParams scan_;
  const LocalFrame* local_frame_;
  const Scene* scene_;
  FlightSummary summary_;
  std::unique_ptr<WordSink> words_;
  std::unique_ptr<PointsCsvWriter> points_csv_;
  std::unique_ptr<LasWriter> points_las_;
  std::unique_ptr<PlyWriter> points_ply_;
  std::unique_ptr<TrajectoryCsvWriter> trajectory_;
  std::unique_ptr<TruthCsvWriter> truth_;
  std::unique_ptr<Quicklook> quicklook_;
  std::unique_ptr<FlightMcapFile> mcap_;
  FrameEncoder encoder_;
  FrameEncoding encoding_;       // add_frame(frame, frame_start)'s, reused per frame
  McapChunk placed_mcap_chunk_;  // add_placed_frame's flight.mcap chunk, reused per frame
  std::int64_t frames_done_ = 0;
  bool resumed_while_finishing_ = false;  // the checkpoint already describes the finished frames
  bool checkpoint_on_disk_ = false;       // this run wrote one, or resumed from one
  bool finished_ = false;
  std::filesystem::path checkpoint_path_;
  Clock::time_point last_checkpoint_;
};

}  // namespace owsim
