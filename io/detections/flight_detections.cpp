#include "io/detections/flight_detections.hpp"

#include <chrono>
#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "io/detections/detections_csv.hpp"
#include "io/detections/recording_detections.hpp"

namespace owsim {
namespace {

constexpr std::size_t kFlushChars = std::size_t{1} << 20;

}  // namespace

DetectorFrame PreparedDetectorFrame::input() const {
  DetectorFrame out;
  out.frame = decoded.frame;
  out.time_s = decoded.sweep.start_s;
  out.aircraft_enu_m = aircraft_enu_m;
  out.returns_enu_m = returns;
  return out;
}

FlightDetections::FlightDetections(const Scenario& scenario, const PoseSource& poses,
                                   std::filesystem::path csv)
    : scenario_(scenario),
      poses_(poses),
      detector_(scenario.detector, scenario.scan.frame_duration_s()),
      file_(std::move(csv)),
      rows_(kDetectionsCsvHeader) {}

DetectionReport& DetectionReport::operator+=(const DetectionReport& other) {
  frames += other.frames;
  pulses += other.pulses;
  returns += other.returns;
  warnings += other.warnings;
  tracks += other.tracks;
  detector_s += other.detector_s;
  return *this;
}

void prepare_detector_frame(const Scenario& scenario, const PoseSource& poses, std::int64_t frame,
                            std::span<const std::uint64_t> milows_words,
                            std::span<const std::uint32_t> hellas_words,
                            std::optional<std::uint32_t> hellas_header_word,
                            PreparedDetectorFrame& out) {
  const ScanParams& scan = scenario.scan;
  const RecordingLayout layout = grid_recording_layout(scan, hellas_header_word);
  DecodedFrame& decoded = out.decoded;
  decoded.frame = frame;
  decoded.first_word =
      layout.first_pulse_word + static_cast<std::uint64_t>(frame * scan.pulses_per_frame());
  if (scan.model == SensorModel::milows) {
    decoded.words.assign(milows_words.begin(), milows_words.end());
  } else {
    decoded.words.assign(hellas_words.begin(), hellas_words.end());
  }
  decode_frame_words(scan, layout, decoded);
  place_detector_frame(scenario, poses, out);
}

void place_detector_frame(const Scenario& scenario, const PoseSource& poses,
                          PreparedDetectorFrame& frame) {
  decoded_returns_enu(frame.decoded, poses, scenario, frame.returns);
  frame.aircraft_enu_m = poses.pose_at(frame.decoded.sweep.start_s).position_enu_m;
}

void FlightDetections::prepare(std::int64_t frame, std::span<const std::uint64_t> milows_words,
                               std::span<const std::uint32_t> hellas_words,
                               std::optional<std::uint32_t> hellas_header_word,
                               PreparedDetectorFrame& out) const {
  prepare_detector_frame(scenario_, poses_, frame, milows_words, hellas_words, hellas_header_word,
                         out);
}

void FlightDetections::add(const PreparedDetectorFrame& frame) {
  if (last_frame_ && frame.decoded.frame != *last_frame_ + 1) {
    throw Error("detections: frame " + std::to_string(frame.decoded.frame) + " given after frame " +
                std::to_string(*last_frame_));
  }
  last_frame_ = frame.decoded.frame;
  const auto start = std::chrono::steady_clock::now();
  const std::span<const ObstacleWarning> warnings = detector_.add_frame(frame.input());
  report_.detector_s +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++report_.frames;
  report_.pulses += frame.decoded.size();
  report_.returns += frame.returns.size();
  report_.warnings += warnings.size();
  for (const ObstacleWarning& warning : warnings) tracks_.insert(warning.track);
  report_.tracks = tracks_.size();
  append_detection_rows(warnings, rows_);
  if (rows_.size() >= kFlushChars) {
    file_.write(rows_);
    rows_.clear();
  }
}

void FlightDetections::add_recording(
    RecordingDecoder& decoder, std::int64_t frames,
    const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  PreparedDetectorFrame frame;
  for (std::int64_t done = 0; done < frames && decoder.next(frame.decoded); ++done) {
    place_detector_frame(scenario_, poses_, frame);
    add(frame);
    if (on_frame) on_frame(report_.frames, report_.pulses);
  }
}

void FlightDetections::replay(const std::filesystem::path& words, std::int64_t frames) {
  if (frames <= 0) return;
  RecordingDecoder decoder(words, scenario_.scan);
  add_recording(decoder, frames);
  if (report_.frames != static_cast<std::uint64_t>(frames)) {
    throw input_error(words.string(), "holds " + std::to_string(report_.frames) +
                                          " frames, not the " + std::to_string(frames) +
                                          " of its checkpoint");
  }
}

void FlightDetections::finish() {
  file_.write(rows_);
  rows_.clear();
  file_.commit();
}

}  // namespace owsim
