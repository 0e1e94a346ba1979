#include "io/run/flight_outputs.hpp"

#include <exception>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/images/png_image.hpp"
#include "io/images/quicklook.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/ply_writer.hpp"
#include "io/points/points_csv_writer.hpp"
#include "io/recording/word_file.hpp"
#include "io/run/flight_mcap.hpp"
#include "io/run/run_checkpoint.hpp"
#include "io/run/summary_json.hpp"
#include "io/run/truth_csv.hpp"
#include "io/trajectory/trajectory_csv_writer.hpp"

namespace owsim {

// The word file of the scenario's sensor: MilOWS 64-bit words, or a HELLAS header word followed
// by 32-bit words.
class WordSink {
 public:
  WordSink(const std::filesystem::path& directory, const ScanParams& scan,
           const WriterCheckpoint* resume_from)
      : pulses_per_frame_(static_cast<std::uint64_t>(scan.pulses_per_frame())) {
    const std::filesystem::path path = directory / word_file_name(scan);
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

  // A frame's words (and the header word before the first), placed by another process.
  void skip_frame() {
    if (milows_) {
      milows_->skip(pulses_per_frame_);
      return;
    }
    hellas_->skip(pulses_per_frame_ + (header_written_ ? 0 : 1));
    header_written_ = true;
  }

  [[nodiscard]] WriterCheckpoint checkpoint() {
    return milows_ ? milows_->checkpoint() : hellas_->checkpoint();
  }

  void commit() {
    if (milows_) milows_->commit();
    if (hellas_) hellas_->commit();
  }

 private:
  std::uint64_t pulses_per_frame_;
  std::optional<WordFileWriter<std::uint64_t>> milows_;
  std::optional<WordFileWriter<std::uint32_t>> hellas_;
  bool header_written_ = false;
};

FlightOutputs::FlightOutputs(const FlightOutputOptions& options, const Scene& scene,
                             const ScanParams& scan, const LocalFrame& local_frame,
                             const RunCheckpoint* resume_from)
    : options_(options),
      scan_(scan),
      local_frame_(&local_frame),
      scene_(&scene),
      // Objects are tallied across frames for summary.json alone (truth.csv takes each frame's).
      summary_(options.outputs.contains(OutputKind::summary) ? named_object_count(scene) : 0),
      encoder_(options_.directory, options_.outputs, scene, scan, local_frame, options.truth),
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
  // An earlier owsim's JSON checkpoint goes too.
  if (checkpointing() && resume_from == nullptr) {
    for (const std::filesystem::path& path :
         {checkpoint_path_, options_.directory / kJsonRunCheckpointFileName}) {
      if (!std::filesystem::remove(path, error) && error) {
        throw input_error(path.string(),
                          "cannot remove an earlier run's checkpoint: " + error.message());
      }
    }
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
  // Resuming a checkpoint written by finish(), a file whose temporary is gone was committed (a
  // link at the temporary's name, even a dangling one, is there: the resume refuses it).
  const auto committed = [&](const std::filesystem::path& final_path) {
    std::error_code ignored;
    return from != nullptr && from->finishing &&
           !std::filesystem::exists(std::filesystem::symlink_status(
               AtomicOutputFile::partial_path_for(final_path), ignored)) &&
           std::filesystem::exists(final_path);
  };
  if (from != nullptr && wants(OutputKind::mcap)) {
    throw input_error(checkpoint_path_.string(),
                      "flight.mcap (output mcap) cannot be continued from a checkpoint; run "
                      "without --resume");
  }
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
    check(wants(OutputKind::d64), directory / word_file_name(scan_), from->words);
    check(wants(OutputKind::csv), directory / "points.csv", from->points_csv);
    check(wants(OutputKind::las), directory / "points.las",
          from->points_las ? std::optional(from->points_las->file) : std::nullopt);
    check(wants(OutputKind::ply), directory / "points.ply", from->points_ply);
    check(wants(OutputKind::trajectory), directory / "trajectory.csv", from->trajectory);
    check(wants(OutputKind::truth), directory / "truth.csv", from->truth);
  }

  if (wants(OutputKind::d64)) {
    const auto* resume = state(&RunCheckpoint::words, word_file_name(scan_));
    if (!committed(directory / word_file_name(scan_))) {
      words_ = std::make_unique<WordSink>(directory, scan_, resume);
    }
  }
  const std::filesystem::path csv = directory / "points.csv";
  if (wants(OutputKind::csv) && !committed(csv)) {
    const auto* resume = state(&RunCheckpoint::points_csv, "points.csv");
    std::vector<std::string> ids = object_ids(scene);
    points_csv_ = std::make_unique<PointsCsvWriter>(
        resume ? PointsCsvWriter::resume(csv, std::move(ids), *resume)
               : PointsCsvWriter(csv, std::move(ids)));
  }
  if (wants(OutputKind::las)) {
    LasWriterOptions las;
    las.origin = local_frame_->origin();
    const std::filesystem::path las_path = directory / "points.las";
    if (const auto* resume = state(&RunCheckpoint::points_las, "points.las");
        !committed(las_path)) {
      points_las_ = std::make_unique<LasWriter>(resume ? LasWriter::resume(las_path, las, *resume)
                                                       : LasWriter(las_path, las));
    }
  }
  const std::filesystem::path ply = directory / "points.ply";
  if (wants(OutputKind::ply) && !committed(ply)) {
    const auto* resume = state(&RunCheckpoint::points_ply, "points.ply");
    points_ply_ =
        std::make_unique<PlyWriter>(resume ? PlyWriter::resume(ply, *resume) : PlyWriter(ply));
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
  if (wants(OutputKind::truth)) {
    const std::filesystem::path path = directory / "truth.csv";
    if (const auto* resume = state(&RunCheckpoint::truth, "truth.csv"); !committed(path)) {
      truth_ = std::make_unique<TruthCsvWriter>(resume ? TruthCsvWriter::resume(path, *resume)
                                                       : TruthCsvWriter(path));
    }
  }
  if (wants(OutputKind::mcap)) {
    mcap_ = std::make_unique<FlightMcapFile>(directory, scene, scan_, options_.sensor_mount);
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
  encoder_.encode_frame(frame, frame_start, out);
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
  if (truth_) truth_->append(encoded.truth_rows, encoded.truth.rows.size());
  if (mcap_) mcap_->append(encoded.mcap.chunk);
  if (quicklook_) {
    quicklook_->add_trajectory_point(encoded.frame_start.position_enu_m);
    quicklook_->add_frame(frame);
  }
  ++frames_done_;
  resumed_while_finishing_ = false;
  if (checkpoint_due()) write_checkpoint(false);
}

void FlightOutputs::add_placed_frame(const PlacedFrame& frame) {
  if (frame.frame != frames_done_) {
    throw Error("outputs: frame " + std::to_string(frame.frame) + " placed, frame " +
                std::to_string(frames_done_) + " expected");
  }
  summary_.add_frame(frame.frame, frame.tally);
  if (words_) words_->skip_frame();
  if (points_csv_) points_csv_->skip(frame.csv_bytes, frame.points);
  if (points_las_) points_las_->skip(frame.las);
  if (points_ply_) points_ply_->skip(frame.points);
  if (trajectory_) trajectory_->write(frame.frame_start);
  if (truth_) truth_->append(frame.truth_rows, frame.truth_row_count);
  if (mcap_) {
    placed_mcap_chunk_.read_finished(frame.mcap_chunk);
    mcap_->append(placed_mcap_chunk_);
  }
  if (quicklook_) quicklook_->add_trajectory_point(frame.frame_start.position_enu_m);
  ++frames_done_;
  resumed_while_finishing_ = false;
}

void FlightOutputs::add_map_hits(std::span<const std::uint8_t> map_mask) {
  if (quicklook_) quicklook_->add_map_hits(map_mask);
}

bool FlightOutputs::checkpoint_due() const {
  return checkpointing() &&
         std::chrono::duration<double>(Clock::now() - last_checkpoint_).count() >=
             options_.checkpoint_interval_s;
}

FlightOutputs::PlacedFiles FlightOutputs::placed_files() {
  // A writer's checkpoint hands its bytes to the kernel and says how many the file holds.
  const auto placed = [](const std::filesystem::path& final_path, const WriterCheckpoint& at) {
    return PlacedFile{AtomicOutputFile::partial_path_for(final_path), at.file_bytes};
  };
  PlacedFiles files;
  const std::filesystem::path& directory = options_.directory;
  if (words_) files.words = placed(directory / word_file_name(scan_), words_->checkpoint());
  if (points_csv_) files.csv = placed(directory / "points.csv", points_csv_->checkpoint());
  if (points_las_) files.las = placed(directory / "points.las", points_las_->checkpoint().file);
  if (points_ply_) files.ply = placed(directory / "points.ply", points_ply_->checkpoint());
  return files;
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
  if (truth_) checkpoint.truth = truth_->checkpoint();
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
  if (truth_) truth_->finish();
  if (mcap_) mcap_->finish();
  if (quicklook_) quicklook_->finish();
  if (!options_.scenario.yaml.empty()) {
    write_input_copies(options_.directory, options_.scenario.inputs);
    AtomicOutputFile scenario(options_.directory / "scenario.yaml");
    scenario.write(options_.scenario.yaml);
    scenario.commit();
  }
  if (wants(OutputKind::summary)) {
    nlohmann::json facts = run_facts;
    facts["pulses_per_frame"] = scan_.pulses_per_frame();
    facts["frame_period_s"] = scan_.frame_duration_s();
    write_summary_json(options_.directory / "summary.json", summary_, *scene_, facts);
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
