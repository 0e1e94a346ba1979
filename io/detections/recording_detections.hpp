#pragma once
// The reference detector run over a recording (INTERFACE.md `owsim detect`, DETECTION-SPEC §1):
// the recorded words decoded frame by frame (io/recording/recording_decoder.hpp), every recorded
// return placed at counter·Δ along its pulse's ray from the navigation pose at the pulse's time —
// what the real processor has, and nothing else — and fed to an ObstacleDetector
// (detection/obstacle_detector.hpp); its warnings are detections.csv. `owsim run` with output
// `detections` runs the same code over the word file it wrote, so the two give the same bytes.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "io/detections/flight_detections.hpp"
#include "io/recording/recording_decoder.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/pose_source.hpp"

namespace owsim {

// The returns of a decoded frame in the local ENU frame: for each pulse but the reference fiber's,
// each counter below the timeout at counter·Δ along the pulse's ray (SENSOR-SPEC §4, §8), the
// sensor placed by `poses` at the pulse's time — exactly at each line's first slot and the next
// line's, linearly between (a line lasts 2.1 ms: the blend errs by ~(h²/8)·|R''|, below 1e-7 rad
// on the examples' turns, far under the encoder's ±0.0018° = 3e-5 rad). Reuses `out`.
void decoded_returns_enu(const DecodedFrame& frame, const PoseSource& poses, const Scenario& scenario,
                         std::vector<Eigen::Vector3d>& out);

// Runs the detector of `scenario.detector` over every remaining frame of `decoder`, the pulses
// placed by `poses`, and writes `csv` (appearing only when complete). `on_frame` (may be empty) is
// told the frames and pulses done after each frame.
DetectionReport detect_recording(RecordingDecoder& decoder, const PoseSource& poses,
                                 const Scenario& scenario, const std::filesystem::path& csv,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& on_frame =
                                     {});

// What `owsim detect` reads of a run folder: its scenario.yaml (the scenario as flown: its
// trajectory, sensor and detector) and its word file (flight.d64 or flight.hellas). Throws
// owsim::Error naming the folder or file for a folder that is not a run's.
struct RunRecording {
  Scenario scenario;
  std::filesystem::path words;
};
[[nodiscard]] RunRecording run_recording(const std::filesystem::path& run_dir);

// `owsim detect RUN_DIR`: the run folder's recording into `csv` (its folder made if need be).
// Throws owsim::Error naming the folder or file for a folder that is not a run's or a recording
// that cannot be decoded; nothing is written then.
DetectionReport detect_run_folder(const std::filesystem::path& run_dir,
                                  const std::filesystem::path& csv,
                                  const std::function<void(std::uint64_t, std::uint64_t)>& on_frame =
                                      {});

// The same for a scenario already loaded and its word file: what `owsim run` does after its frames.
DetectionReport detect_word_file(const Scenario& scenario, const std::filesystem::path& words,
                                 const std::filesystem::path& csv,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& on_frame =
                                     {});

}  // namespace owsim
