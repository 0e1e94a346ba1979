#pragma once
// The reference obstacle detector (DETECTION-SPEC, docs/detection.md) as a library object fed
// frame by frame, beside Simulation:
//
//   owsim::Simulation sim = owsim::Simulation::open("corridor.yaml");
//   owsim::FrameDetector detector(sim);  // the scenario's `detector:` section
//   owsim::Frame frame;
//   for (std::int64_t k = 0; k < sim.frame_count(); ++k) {
//     sim.simulate_frame(k, frame);
//     for (const owsim::ObstacleWarning& w : detector.add_frame(frame)) { /* w.kind, w.track … */ }
//   }
//
// It reads what `owsim run --outputs detections` reads — the frame's words, decoded on the
// scenario's pulse grid, and the navigation pose (the scenario's trajectory as the aircraft knows
// it) — never the truth in Frame::returns(), so its warnings are detections.csv's rows, byte for
// byte (csv_rows). Frames simulated with host poses (Simulation::simulate_frame(k, poses)) are
// placed by the scenario's trajectory all the same: give such a host's detector its own poses
// through a scenario trajectory, or place the words itself. Not thread-safe: one detector, one
// thread, frames in order.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "detection/obstacle_detector.hpp"
#include "io/detections/flight_detections.hpp"

namespace owsim {

class Simulation;
class Frame;

class FrameDetector {
 public:
  // `simulation` must outlive the detector. Throws owsim::Error for a bad `detector:` section.
  explicit FrameDetector(const Simulation& simulation);

  // The warnings after `frame` (each frame once, in order from any first one; otherwise
  // owsim::Error), by track id; valid until the next call.
  std::span<const ObstacleWarning> add_frame(const Frame& frame);
  // The last add_frame's warnings as detections.csv rows (DETECTION-SPEC §5), without the header.
  [[nodiscard]] std::string csv_rows() const;
  // detections.csv's header line, with its newline.
  [[nodiscard]] static std::string_view csv_header();

 private:
  const Simulation& simulation_;
  ObstacleDetector detector_;
  PreparedDetectorFrame prepared_;
  std::span<const ObstacleWarning> warnings_;
  std::optional<std::int64_t> last_frame_;
};

}  // namespace owsim
