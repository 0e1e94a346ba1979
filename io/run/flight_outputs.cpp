#include "io/run/flight_outputs.hpp"

#include <exception>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/json_text.hpp"
#include "io/images/png_image.hpp"
#include "io/images/quicklook.hpp"
#include "io/points/frame_points.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/ply_writer.hpp"
#include "io/points/points_csv_writer.hpp"
#include "io/recording/frame_words.hpp"
#include "io/recording/word_file.hpp"
#include "io/run/run_checkpoint.hpp"
#include "io/trajectory/trajectory_csv_writer.hpp"

namespace owsim {

// The word file of the scenario's sensor: MilOWS 64-bit words, or a HELLAS header word followed
// by 32-bit words.
class WordSink {
 public:
  WordSink(const std::filesystem::path& directory, const ScanParams& scan,
           const WriterCheckpoint* resume_from)
      : scan_(scan) {
    const std::filesystem::path path = directory / file_name(scan);
    if (scan.model == SensorModel::milows) {
      if (resume_from != nullptr) {
        milows_.emplace(WordFileWriter<std::uint64_t>::resume(path, *resume_from));
      } else {
        milows_.emplace(path);
      }
    } else {
      if (resume_from != nullptr) {
        hellas_.emplace(WordFileWriter<std::uint32_t>::resume(path, *resume_from));
        header_written_ = resume_from->records > 0;
      } else {
        hellas_.emplace(path);
      }
    }
  }

  [[nodiscard]] static std::string_view file_name(const ScanParams& scan) {
    return scan.model == SensorModel::milows ? "flight.d64" : "flight.hellas";
  }

  // The word buffer of `out` sized for a frame (once per encoding).
  void size(FrameEncoding& out) const {
    const auto pulses = static_cast<std::size_t>(scan_.pulses_per_frame());
    if (scan_.model == SensorModel::milows) {
      out.milows_words.resize(pulses);
    } else {
      out.hellas_words.resize(pulses);
    }
  }

  // The words of pulses [first, first + count) into their places in `out` (sized; reads only
  // scan_: safe on any thread beside append(), concurrently for disjoint pulses).
  void encode(const FrameView& frame, std::size_t first, std::size_t count,
              FrameEncoding& out) const {
    const auto pulses = frame.pulses.subspan(first, count);
    const auto returns = frame.returns.subspan(first, count);
    if (scan_.model == SensorModel::milows) {
      pack_milows_frame(pulses, returns,
                        std::span<std::uint64_t>(out.milows_words).subspan(first, count));
      return;
    }
    pack_hellas_frame(scan_, frame.sweep, pulses, returns,
                      std::span<std::uint32_t>(out.hellas_words).subspan(first, count));
  }

  // What the file takes once from a frame: the HELLAS header word, before the first frame.
  void encode_header(const FrameView& frame, FrameEncoding& out) const {
    if (scan_.model == SensorModel::hellas) {
      out.hellas_header_word = hellas_file_header_word(frame.sweep, frame.pulses.front().time_s);
    }
  }

  void append(const FrameEncoding& encoded) {
    if (milows_) {
      milows_->write(std::span<const std::uint64_t>(encoded.milows_words));
      return;
    }
    if (!header_written_) {
      hellas_->write(encoded.hellas_header_word);
      header_written_ = true;
    }
    hellas_->write(std::span<const std::uint32_t>(encoded.hellas_words));
  }

  [[nodiscard]] WriterCheckpoint checkpoint() {
    return milows_ ? milows_->checkpoint() : hellas_->checkpoint();
  }

  void commit() {
    if (milows_) milows_->commit();
    if (hellas_) hellas_->commit();
  }

 private:
  ScanParams scan_;
  std::optional<WordFileWriter<std::uint64_t>> milows_;
  std::optional<WordFileWriter<std::uint32_t>> hellas_;
  bool header_written_ = false;
};

std::set<OutputKind> all_outputs() {
  return {OutputKind::d64, OutputKind::points, OutputKind::trajectory, OutputKind::summary,
          OutputKind::quicklook};
}

std::set<OutputKind> parse_output_list(std::string_view list) {
  std::set<OutputKind> kinds;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string_view item = list.substr(begin, comma - begin);
    if (item == "d64") {
      kinds.insert(OutputKind::d64);
    } else if (item == "points") {
      kinds.insert(OutputKind::points);
    } else if (item == "trajectory") {
      kinds.insert(OutputKind::trajectory);
    } else if (item == "summary") {
      kinds.insert(OutputKind::summary);
    } else if (item == "quicklook") {
      kinds.insert(OutputKind::quicklook);
    } else {
      throw input_error("--outputs",
                        "unknown output '" + std::string(item) +
                            "' (expected d64, points, trajectory, summary, quicklook)");
    }
    begin = comma + 1;
  }
  return kinds;
}

FlightOutputs::FlightOutputs(const FlightOutputOptions& options, const Scene& scene,
                             const ScanParams& scan, const LocalFrame& local_frame,
                             const RunCheckpoint* resume_from)
    : options_(options),
      scan_(scan),
      local_frame_(&local_frame),
      summary_(scene),
      checkpoint_path_(run_checkpoint_path(options_.directory)),
      last_checkpoint_(Clock::now()) {
  // The images' optional module (OpenImageIO) is loaded before anything is written or removed.
  if (wants(OutputKind::quicklook)) require_png_encoder();
  std::error_code error;
  std::filesystem::create_directories(options_.directory, error);
  if (error) {
    throw file_error(options_.directory.string(),
                     "cannot create the output folder: " + error.message());
  }
  // A checkpoint of another run must not outlive the temporaries this run is about to truncate.
  if (checkpointing() && resume_from == nullptr &&
      (!std::filesystem::remove(checkpoint_path_, error) && error)) {
    throw input_error(checkpoint_path_.string(),
                      "cannot remove an earlier run's checkpoint: " + error.message());
  }
  open_outputs(scene, resume_from);
}

void FlightOutputs::open_outputs(const Scene& scene, const RunCheckpoint* from) {
  const std::filesystem::path& directory = options_.directory;
  // The state `from` holds for an output, or nullptr for a fresh file.
  const auto state = [&]<typename State>(std::optional<State> RunCheckpoint::*member,
                                         std::string_view name) -> const State* {
    if (from == nullptr) return nullptr;
    if (!(from->*member)) {
      throw input_error(checkpoint_path_.string(),
                        "holds no state for " + std::string(name) + "; run without --resume");
    }
    return &*(from->*member);
  };
  // Resuming a checkpoint written by finish(), a file whose temporary is gone was committed.
  const auto committed = [&](const std::filesystem::path& final_path) {
    return from != nullptr && from->finishing &&
           !std::filesystem::exists(AtomicOutputFile::partial_path_for(final_path)) &&
           std::filesystem::exists(final_path);
  };
  if (from != nullptr) {
    if (from->summary.counts.frames != static_cast<std::uint64_t>(from->frames_done)) {
      throw input_error(checkpoint_path_.string(),
                        "damaged checkpoint: " + std::to_string(from->frames_done) +
                            " frames done, the summary holds " +
                            std::to_string(from->summary.counts.frames));
    }
    try {
      summary_.restore(from->summary);
    } catch (const Error& e) {
      throw input_error(checkpoint_path_.string(), e.what());
    }
    frames_done_ = from->frames_done;
    resumed_while_finishing_ = from->finishing;
    checkpoint_on_disk_ = true;
    // Every temporary is checked before any is cut back: a refused resume touches nothing.
    const auto check = [&](bool wanted, const std::filesystem::path& final_path,
                           const std::optional<WriterCheckpoint>& writer) {
      if (wanted && writer && !committed(final_path)) {
        AtomicOutputFile::require_resumable(final_path, writer->file_bytes);
      }
    };
    const bool points = wants(OutputKind::points);
    check(wants(OutputKind::d64), directory / WordSink::file_name(scan_), from->words);
    check(points, directory / "points.csv", from->points_csv);
    check(points, directory / "points.las",
          from->points_las ? std::optional(from->points_las->file) : std::nullopt);
    check(points, directory / "points.ply", from->points_ply);
    check(wants(OutputKind::trajectory), directory / "trajectory.csv", from->trajectory);
  }

  if (wants(OutputKind::d64)) {
    const auto* resume = state(&RunCheckpoint::words, WordSink::file_name(scan_));
    if (!committed(directory / WordSink::file_name(scan_))) {
      words_ = std::make_unique<WordSink>(directory, scan_, resume);
    }
  }
  if (wants(OutputKind::points)) {
    std::vector<std::string> ids = object_ids(scene);
    const std::filesystem::path csv = directory / "points.csv";
    if (const auto* resume = state(&RunCheckpoint::points_csv, "points.csv"); !committed(csv)) {
      points_csv_ = std::make_unique<PointsCsvWriter>(
          resume ? PointsCsvWriter::resume(csv, std::move(ids), *resume)
                 : PointsCsvWriter(csv, std::move(ids)));
    }
    LasWriterOptions las;
    las.origin = local_frame_->origin();
    const std::filesystem::path las_path = directory / "points.las";
    if (const auto* resume = state(&RunCheckpoint::points_las, "points.las");
        !committed(las_path)) {
      points_las_ = std::make_unique<LasWriter>(resume ? LasWriter::resume(las_path, las, *resume)
                                                       : LasWriter(las_path, las));
    }
    const std::filesystem::path ply = directory / "points.ply";
    if (const auto* resume = state(&RunCheckpoint::points_ply, "points.ply"); !committed(ply)) {
      points_ply_ =
          std::make_unique<PlyWriter>(resume ? PlyWriter::resume(ply, *resume) : PlyWriter(ply));
    }
  }
  if (wants(OutputKind::trajectory)) {
    const std::filesystem::path path = directory / "trajectory.csv";
    if (const auto* resume = state(&RunCheckpoint::trajectory, "trajectory.csv");
        !committed(path)) {
      trajectory_ = std::make_unique<TrajectoryCsvWriter>(
          resume ? TrajectoryCsvWriter::resume(path, *local_frame_, *resume)
                 : TrajectoryCsvWriter(path, *local_frame_));
    }
  }
  if (wants(OutputKind::quicklook)) {
    QuicklookOptions quicklook;
    quicklook.every_nth_frame = options_.quicklook_every_nth_frame;
    const Eigen::AlignedBox2d region =
        options_.map_region.isEmpty() ? quicklook_map_region(scene, {}) : options_.map_region;
    quicklook_ =
        std::make_unique<Quicklook>(directory / "quicklook", scene, scan_, region, quicklook);
    if (const auto* resume = state(&RunCheckpoint::quicklook, "quicklook/")) {
      try {
        quicklook_->restore(*resume);
      } catch (const Error& e) {
        throw input_error(checkpoint_path_.string(), e.what());
      }
    }
  }
}

FlightOutputs::~FlightOutputs() {
  if (checkpointing() && !finished_) {
    std::error_code ignored;
    std::filesystem::remove(checkpoint_path_, ignored);
  }
}

void FlightOutputs::add_frame(const FrameView& frame, const Pose& frame_start) {
  encode_frame(frame, frame_start, encoding_);
  add_frame(frame, encoding_);
}

void FlightOutputs::encode_frame(const FrameView& frame, const Pose& frame_start,
                                 FrameEncoding& out) const {
  size_encoding(out);
  encode_pulses(frame, 0, static_cast<int>(frame.pulses.size()), out);
  finish_encoding(frame, frame_start, out);
}

void FlightOutputs::size_encoding(FrameEncoding& out) const {
  if (words_) words_->size(out);
  out.line_blocks.resize(static_cast<std::size_t>(scan_.lines_per_frame));
}

void FlightOutputs::encode_pulses(const FrameView& frame, int begin, int end,
                                  FrameEncoding& out) const {
  const int pulses = scan_.pulses_per_frame();
  const int fibers = scan_.fibers_per_line;
  if (begin < 0 || begin >= end || end > pulses || begin % fibers != 0 ||
      (end % fibers != 0 && end != pulses) ||
      frame.pulses.size() != static_cast<std::size_t>(pulses) ||
      frame.returns.size() != frame.pulses.size() ||
      out.line_blocks.size() != static_cast<std::size_t>(scan_.lines_per_frame)) {
    throw Error("outputs: pulses " + std::to_string(begin) + ".." + std::to_string(end) +
                " are not whole lines of a frame of this scan, or the encoding is not sized");
  }
  // The block's tally and error go to the entry of its first line; its other lines' are emptied.
  const int first_line = begin / fibers;
  const int end_line = (end + fibers - 1) / fibers;
  for (int line = first_line + 1; line < end_line; ++line) {
    FrameEncoding::LineBlock& empty = out.line_blocks[static_cast<std::size_t>(line)];
    summary_.tally({}, {}, empty.tally);
    empty.error = nullptr;
  }
  FrameEncoding::LineBlock& block = out.line_blocks[static_cast<std::size_t>(first_line)];
  block.error = nullptr;
  try {
    const auto first = static_cast<std::size_t>(begin);
    const auto count = static_cast<std::size_t>(end - begin);
    // The tally feeds summary.json alone: without that output, the block's tally stays empty.
    const std::size_t tallied = wants(OutputKind::summary) ? count : 0;
    summary_.tally(frame.pulses.subspan(first, tallied), frame.returns.subspan(first, tallied),
                   block.tally);
    if (words_) words_->encode(frame, first, count, out);
  } catch (...) {
    block.error = std::current_exception();
  }
}

void FlightOutputs::finish_encoding(const FrameView& frame, const Pose& frame_start,
                                    FrameEncoding& out) const {
  out.frame = frame.frame;
  out.frame_start = frame_start;
  out.error = nullptr;
  // The blocks' parts in line order: the first error, and the tally as one pass would give it.
  summary_.tally({}, {}, out.tally);
  for (const FrameEncoding::LineBlock& block : out.line_blocks) {
    if (block.error && !out.error) out.error = block.error;
    out.tally.append(block.tally);
  }
  if (out.error) return;
  try {
    if (words_) words_->encode_header(frame, out);
    if (points_csv_ || points_las_ || points_ply_) {
      frame_points(frame, *local_frame_, out.points);
      if (points_csv_) {
        out.csv_rows.clear();
        points_csv_->encode(out.points, out.csv_rows);
      }
      if (points_las_) points_las_->encode(out.points, out.las);
      if (points_ply_) PlyWriter::encode(out.points, out.ply_vertices);
    }
  } catch (...) {
    out.error = std::current_exception();
  }
}

void FlightOutputs::add_frame(const FrameView& frame, const FrameEncoding& encoded) {
  if (frame.frame != frames_done_) {
    throw Error("outputs: frame " + std::to_string(frame.frame) + " given, frame " +
                std::to_string(frames_done_) + " expected");
  }
  if (encoded.frame != frame.frame) {
    throw Error("outputs: frame " + std::to_string(frame.frame) +
                " given with the encoding of frame " + std::to_string(encoded.frame));
  }
  if (encoded.error) std::rethrow_exception(encoded.error);
  summary_.add_frame(frame.frame, encoded.tally);
  if (words_) words_->append(encoded);
  if (points_csv_) points_csv_->append(encoded.csv_rows, encoded.points.size());
  if (points_las_) points_las_->append(encoded.las);
  if (points_ply_) points_ply_->append(encoded.ply_vertices);
  if (trajectory_) trajectory_->write(encoded.frame_start);
  if (quicklook_) {
    quicklook_->add_trajectory_point(encoded.frame_start.position_enu_m);
    quicklook_->add_frame(frame);
  }
  ++frames_done_;
  resumed_while_finishing_ = false;
  if (checkpointing() && std::chrono::duration<double>(Clock::now() - last_checkpoint_).count() >=
                             options_.checkpoint_interval_s) {
    write_checkpoint(false);
  }
}

void FlightOutputs::write_checkpoint(bool finishing) {
  checkpoint_on_disk_ = true;
  RunCheckpoint checkpoint;
  checkpoint.run = options_.checkpoint_run;
  checkpoint.frames_done = frames_done_;
  checkpoint.finishing = finishing;
  checkpoint.summary = summary_.checkpoint();
  if (words_) checkpoint.words = words_->checkpoint();
  if (points_csv_) checkpoint.points_csv = points_csv_->checkpoint();
  if (points_las_) checkpoint.points_las = points_las_->checkpoint();
  if (points_ply_) checkpoint.points_ply = points_ply_->checkpoint();
  if (trajectory_) checkpoint.trajectory = trajectory_->checkpoint();
  if (quicklook_) checkpoint.quicklook = quicklook_->checkpoint();
  write_run_checkpoint(checkpoint_path_, checkpoint);
  last_checkpoint_ = Clock::now();
}

void FlightOutputs::finish(const nlohmann::json& run_facts) {
  // From here files appear under their final names; a resume must know they may have. A run that
  // never wrote a checkpoint (shorter than the interval) writes none now either: a resume finds
  // none and starts from frame 0, which gives the same bytes, and a short run (a one-frame run of
  // a thousand-member sweep) does not pay for serialising every object's state.
  if (checkpointing() && checkpoint_on_disk_ && !resumed_while_finishing_) write_checkpoint(true);
  if (words_) words_->commit();
  if (points_csv_) points_csv_->finish();
  if (points_las_) points_las_->finish();
  if (points_ply_) points_ply_->finish();
  if (trajectory_) trajectory_->finish();
  if (quicklook_) quicklook_->finish();
  if (wants(OutputKind::summary)) {
    nlohmann::json summary = run_facts;
    summary.update(summary_.to_json());
    summary["pulses_per_frame"] = scan_.pulses_per_frame();
    AtomicOutputFile file(options_.directory / "summary.json");
    file.write(json_text(summary, 2) + "\n");
    file.commit();
  }
  finished_ = true;
  if (checkpointing()) {
    // Best effort: a checkpoint left now describes committed files, and resuming it only rewrites
    // summary.json and the map. Its temporary is there if an earlier process died writing it.
    std::error_code ignored;
    std::filesystem::remove(checkpoint_path_, ignored);
    std::filesystem::remove(AtomicOutputFile::partial_path_for(checkpoint_path_), ignored);
  }
}

}  // namespace owsim
