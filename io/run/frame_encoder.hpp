#pragma once
// One frame's bytes for every output `owsim run` writes (io/run/flight_outputs.hpp), encoded
// without the files: the sensor words, points.csv rows, points.las records, points.ply vertices
// the frame's part of summary.json and its chunk of flight.mcap. Every method is const and may run
// on any thread, concurrently with itself (each call with its own FrameEncoding), so the costly
// part of the outputs runs on the pipeline's parallel stage, and on every process of a distributed
// run (distributed/), not only where the files are.
#include <filesystem>
#include <optional>
#include <set>

#include "geometry/geodesy_cells.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/points_csv_writer.hpp"
#include "io/run/flight_mcap.hpp"
#include "io/run/flight_summary.hpp"
#include "io/run/frame_encoding.hpp"
#include "io/run/output_kind.hpp"
#include "io/run/truth_csv.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

class FrameEncoder {
 public:
  // The encoder of the `outputs` of a run into `directory` (which names the files in errors).
  // truth.csv is encoded only with a `truth` source (which must outlive the encoder); without one
  // the output is dropped. Throws owsim::Error as LasWriter does for an origin points.las cannot
  // hold.
  FrameEncoder(const std::filesystem::path& directory, const std::set<OutputKind>& outputs,
               const Scene& scene, const ScanParams& scan, const LocalFrame& local_frame,
               const FrameTruthSource* truth = nullptr);

  // encode_frame() in three steps, so the per-pulse part (the words and the summary tally) runs on
  // each block of a frame while the simulation has it in cache (FrameBlockDone of
  // engine/frame_simulator.hpp): size_encoding() sizes an encoding's buffers for this scan, once;
  // encode_pulses() encodes a block of the frame — `block` holds the records of pulses [begin,
  // begin + block.pulses.size()), whole lines, and nothing else — concurrently for disjoint blocks
  // of the frame (every line in exactly one block), an error kept in `out`; after the frame's last
  // block, finish_encoding() does the rest. The result is encode_frame()'s. encode_pulses throws
  // owsim::Error if the pulses are not whole lines of a frame of this scan or `out` is not sized.
  // finish_encoding() reads the frame's records only when reads_frame_records(): otherwise
  // `frame` need hold only its index and sweep (FrameRecordScope::block).
  void size_encoding(FrameEncoding& out) const;
  void encode_pulses(const FrameView& block, int begin, FrameEncoding& out) const;
  void finish_encoding(const FrameView& frame, const Pose& frame_start, FrameEncoding& out) const;
  // All three for a whole frame; `frame_start` is the aircraft's pose at its first pulse. An
  // error is kept in `out`, not thrown.
  void encode_frame(const FrameView& frame, const Pose& frame_start, FrameEncoding& out) const;

  [[nodiscard]] bool wants(OutputKind kind) const { return outputs_.contains(kind); }
  [[nodiscard]] bool wants_points() const { return owsim::wants_points(outputs_); }
  // Whether a frame's points are made: for a point file or flight.mcap.
  [[nodiscard]] bool makes_points() const { return wants_points() || mcap_.has_value(); }
  // Whether finish_encoding() reads the frame's per-pulse records (its points do).
  [[nodiscard]] bool reads_frame_records() const { return makes_points(); }
  [[nodiscard]] const ScanParams& scan() const { return scan_; }

 private:
  std::set<OutputKind> outputs_;
  ScanParams scan_;
  GeodesyCells geodesy_;      // with the LAS grid when points.las is written
  std::size_t object_count_;  // named_object_count: FlightSummary's objects, for its tally
  std::optional<PointsCsvRows> csv_;
  std::optional<LasPointEncoder> las_;
  const FrameTruthSource* truth_ = nullptr;
  std::optional<TruthCsvRows> truth_rows_;
  std::optional<FlightMcapEncoder> mcap_;
};

}  // namespace owsim
