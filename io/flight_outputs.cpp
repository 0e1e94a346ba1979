#include "io/flight_outputs.hpp"

#include <sstream>
#include <vector>

#include "geometry/error.hpp"
#include "io/atomic_output_file.hpp"
#include "io/frame_points.hpp"
#include "io/frame_words.hpp"
#include "io/las_writer.hpp"
#include "io/ply_writer.hpp"
#include "io/quicklook.hpp"
#include "io/points_csv_writer.hpp"
#include "io/trajectory_csv_writer.hpp"
#include "io/word_file.hpp"

namespace owsim {

// The word file of the scenario's sensor: MilOWS 64-bit words, or a HELLAS header word followed
// by 32-bit words.
class WordSink {
 public:
  WordSink(const std::filesystem::path& directory, const ScanParams& scan) : scan_(scan) {
    if (scan.model == SensorModel::milows) {
      milows_.emplace(directory / "flight.d64");
      milows_words_.resize(static_cast<std::size_t>(scan.pulses_per_frame()));
    } else {
      hellas_.emplace(directory / "flight.hellas");
      hellas_words_.resize(static_cast<std::size_t>(scan.pulses_per_frame()));
    }
  }

  void add_frame(const FrameView& frame) {
    if (milows_) {
      pack_milows_frame(frame.pulses, frame.returns, milows_words_);
      milows_->write(std::span<const std::uint64_t>(milows_words_));
      return;
    }
    if (!header_written_) {
      hellas_->write(hellas_file_header_word(frame.sweep, frame.pulses.front().time_s));
      header_written_ = true;
    }
    pack_hellas_frame(scan_, frame.sweep, frame.pulses, frame.returns, hellas_words_);
    hellas_->write(std::span<const std::uint32_t>(hellas_words_));
  }

  void commit() {
    if (milows_) milows_->commit();
    if (hellas_) hellas_->commit();
  }

 private:
  ScanParams scan_;
  std::optional<WordFileWriter<std::uint64_t>> milows_;
  std::optional<WordFileWriter<std::uint32_t>> hellas_;
  std::vector<std::uint64_t> milows_words_;
  std::vector<std::uint32_t> hellas_words_;
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
      throw input_error("--outputs", "unknown output '" + std::string(item) +
                                         "' (expected d64, points, trajectory, summary, quicklook)");
    }
    begin = comma + 1;
  }
  return kinds;
}

FlightOutputs::FlightOutputs(const FlightOutputOptions& options, const Scene& scene,
                             const ScanParams& scan, const LocalFrame& local_frame)
    : options_(options), scan_(scan), local_frame_(&local_frame), summary_(scene) {
  std::error_code error;
  std::filesystem::create_directories(options_.directory, error);
  if (error) {
    throw input_error(options_.directory.string(), "cannot create the output folder: " +
                                                       error.message());
  }
  if (wants(OutputKind::d64)) words_ = std::make_unique<WordSink>(options_.directory, scan_);
  if (wants(OutputKind::points)) {
    std::vector<std::string> ids;
    for (const Conductor& conductor : scene.conductors) ids.push_back(conductor.id);
    for (const Cylinder& cylinder : scene.cylinders) ids.push_back(cylinder.id);
    ids.emplace_back("terrain");  // the ground's object index comes last
    point_sinks_.push_back(
        std::make_unique<PointsCsvWriter>(options_.directory / "points.csv", std::move(ids)));
    LasWriterOptions las;
    las.origin = local_frame.origin();
    point_sinks_.push_back(std::make_unique<LasWriter>(options_.directory / "points.las", las));
    point_sinks_.push_back(std::make_unique<PlyWriter>(options_.directory / "points.ply"));
  }
  if (wants(OutputKind::trajectory)) {
    trajectory_ =
        std::make_unique<TrajectoryCsvWriter>(options_.directory / "trajectory.csv", local_frame);
  }
  if (wants(OutputKind::quicklook)) {
    QuicklookOptions quicklook;
    quicklook.every_nth_frame = options_.quicklook_every_nth_frame;
    const Eigen::AlignedBox2d region =
        options_.map_region.isEmpty() ? quicklook_map_region(scene, {}) : options_.map_region;
    quicklook_ = std::make_unique<Quicklook>(options_.directory / "quicklook", scene, scan_, region,
                                             quicklook);
  }
}

FlightOutputs::~FlightOutputs() = default;

void FlightOutputs::add_frame(const FrameView& frame, const Pose& frame_start) {
  summary_.add_frame(frame.frame, frame.pulses, frame.returns);
  if (words_) words_->add_frame(frame);
  if (!point_sinks_.empty()) {
    frame_points(frame, *local_frame_, points_);
    for (auto& sink : point_sinks_) sink->write(points_);
  }
  if (trajectory_) trajectory_->write(frame_start);
  if (quicklook_) {
    quicklook_->add_trajectory_point(frame_start.position_enu_m);
    quicklook_->add_frame(frame);
  }
}

void FlightOutputs::finish(const nlohmann::json& run_facts) {
  if (words_) words_->commit();
  for (auto& sink : point_sinks_) sink->finish();
  if (trajectory_) trajectory_->finish();
  if (quicklook_) quicklook_->finish();
  if (wants(OutputKind::summary)) {
    nlohmann::json summary = run_facts;
    summary.update(summary_.to_json());
    summary["pulses_per_frame"] = scan_.pulses_per_frame();
    AtomicOutputFile file(options_.directory / "summary.json");
    file.write(summary.dump(2) + "\n");
    file.commit();
  }
}

}  // namespace owsim
