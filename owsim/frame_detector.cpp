#include "owsim/frame_detector.hpp"

#include "geometry/error.hpp"
#include "io/detections/detections_csv.hpp"
#include "io/recording/frame_words.hpp"
#include "owsim/flight_setup.hpp"
#include "owsim/frame.hpp"
#include "owsim/simulation.hpp"

namespace owsim {

FrameDetector::FrameDetector(const Simulation& simulation)
    : simulation_(simulation),
      detector_(simulation.scenario().detector, simulation.scenario().scan.frame_duration_s()) {}

std::span<const ObstacleWarning> FrameDetector::add_frame(const Frame& frame) {
  if (last_frame_ && frame.index() != *last_frame_ + 1) {
    throw Error("FrameDetector: frame " + std::to_string(frame.index()) + " given after frame " +
                std::to_string(*last_frame_) + " (frames go in order, each once)");
  }
  // The HELLAS word file's header word precedes frame 0; its β code places that frame's first line.
  std::optional<std::uint32_t> header;
  if (frame.model() == SensorModel::hellas && frame.index() == 0 && !frame.pulses().empty()) {
    header = hellas_file_header_word(frame.sweep(), frame.pulses().front().time_s);
  }
  const FlightSetup& setup = simulation_.setup();
  prepare_detector_frame(setup.scenario, setup.trajectory, frame.index(), frame.milows_words(),
                         frame.hellas_words(), header, prepared_);
  warnings_ = detector_.add_frame(prepared_.input());
  last_frame_ = frame.index();
  return warnings_;
}

std::string FrameDetector::csv_rows() const {
  std::string rows;
  append_detection_rows(warnings_, rows);
  return rows;
}

std::string_view FrameDetector::csv_header() { return kDetectionsCsvHeader; }

}  // namespace owsim
