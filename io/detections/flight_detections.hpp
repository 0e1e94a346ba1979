#pragma once
// detections.csv written as a flight goes (`owsim run` output `detections`, INTERFACE.md "Obstacle
// warnings"): each frame's words, as the run encoded them, decoded as `owsim detect` decodes the
// word file (io/recording/recording_decoder.hpp decode_frame_words on the scenario's pulse grid),
// their returns placed by the navigation (io/detections/recording_detections.hpp), and the
// detector fed in frame order — so the file is the bytes `owsim detect` writes from the finished
// folder. The costly part (decoding, placing ~10,000 returns a frame) runs where the frame was
// simulated, on the pipeline's parallel stage; only the detector itself runs in frame order.
//
// A resumed run (--resume) replays the frames its checkpoint holds from the word file's temporary
// through the detector, rewriting the rows of those frames, and goes on from there.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "detection/obstacle_detector.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/recording/recording_decoder.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/pose_source.hpp"

namespace owsim {

struct DetectionReport {
  std::uint64_t frames = 0;
  std::uint64_t pulses = 0;
  std::uint64_t returns = 0;
  std::uint64_t warnings = 0;  // rows of detections.csv
  std::uint64_t tracks = 0;    // tracks that warned at least once
  // Wall seconds inside the detector (ObstacleDetector::add_frame), on the one thread that runs
  // it: `owsim bench`'s detector figure. Not in any file.
  double detector_s = 0.0;
  // Sums another flight's report into this one (tracks as counted in each flight).
  DetectionReport& operator+=(const DetectionReport& other);
};

// What the detector reads of one frame, prepared on any thread.
struct PreparedDetectorFrame {
  DecodedFrame decoded;
  std::vector<Eigen::Vector3d> returns;
  DetectorFrame input() const;
  Eigen::Vector3d aircraft_enu_m = Eigen::Vector3d::Zero();
};

// Frame `frame`'s words as a run encoded them (MilOWS or HELLAS; for frame 0 of a HELLAS run, the
// file's header word) into what the detector reads: decoded on the scenario's pulse grid and placed
// by `poses`. Thread-safe; each call its own `out`.
void prepare_detector_frame(const Scenario& scenario, const PoseSource& poses, std::int64_t frame,
                            std::span<const std::uint64_t> milows_words,
                            std::span<const std::uint32_t> hellas_words,
                            std::optional<std::uint32_t> hellas_header_word,
                            PreparedDetectorFrame& out);

// `frame.decoded`'s returns placed by `poses` and the aircraft's position at its start: the rest of
// what the detector reads (prepare_detector_frame's second half; a decoder's frames need only it).
void place_detector_frame(const Scenario& scenario, const PoseSource& poses,
                          PreparedDetectorFrame& frame);

class FlightDetections {
 public:
  // `scenario` (its sensor, mount, counter and detector) and `poses` (its trajectory) must outlive
  // this. Creates `csv`'s temporary (io/files/atomic_output_file.hpp); throws owsim::Error.
  FlightDetections(const Scenario& scenario, const PoseSource& poses, std::filesystem::path csv);

  // prepare_detector_frame with this flight's scenario and poses.
  void prepare(std::int64_t frame, std::span<const std::uint64_t> milows_words,
               std::span<const std::uint32_t> hellas_words,
               std::optional<std::uint32_t> hellas_header_word, PreparedDetectorFrame& out) const;
  // The detector on the next frame (each frame the one after the last); its rows appended to the
  // file.
  void add(const PreparedDetectorFrame& frame);
  // The frames `decoder` has left, at most `frames` of them, through the detector; `on_frame` (may
  // be empty) told the frames and pulses done after each.
  void add_recording(RecordingDecoder& decoder,
                     std::int64_t frames = std::numeric_limits<std::int64_t>::max(),
                     const std::function<void(std::uint64_t, std::uint64_t)>& on_frame = {});
  // The first `frames` frames of the word file at `words` (a resumed run's temporary, cut back to
  // its checkpoint) through the detector, as if the run had just made them. Throws owsim::Error
  // naming the file if it holds fewer.
  void replay(const std::filesystem::path& words, std::int64_t frames);
  // Completes detections.csv under its final name.
  void finish();

  [[nodiscard]] const DetectionReport& report() const { return report_; }

 private:
  const Scenario& scenario_;
  const PoseSource& poses_;
  ObstacleDetector detector_;
  AtomicOutputFile file_;
  std::string rows_;
  std::optional<std::int64_t> last_frame_;
  DetectionReport report_;
  std::set<std::int64_t> tracks_;
};

}  // namespace owsim
