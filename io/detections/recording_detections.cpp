#include "io/detections/recording_detections.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <system_error>

#include "detection/obstacle_detector.hpp"
#include "geometry/error.hpp"
#include "io/detections/detections_csv.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/run/output_kind.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/mounting.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

constexpr std::size_t kFlushChars = std::size_t{1} << 20;

}  // namespace

void decoded_returns_enu(const DecodedFrame& frame, const PoseSource& poses, const Scenario& scenario,
                         std::vector<Eigen::Vector3d>& out) {
  const RangeCounterParams& counter = scenario.receiver.counter;
  // Two slots a pulse, NaN where it holds no return; compacted in pulse order below.
  std::vector<Eigen::Vector3d> slots(
      2 * frame.size(), Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frame.size(), 512), [&](const auto& range) {
    for (std::size_t j = range.begin(); j < range.end(); ++j) {
      const Pulse& pulse = frame.pulses[j];
      const std::uint16_t counts[2] = {frame.counter1[j], frame.counter2[j]};
      if (pulse.reference ||
          (counts[0] >= counter.timeout_counts && counts[1] >= counter.timeout_counts)) {
        continue;
      }
      const SensorPlacement placement =
          sensor_placement(poses.pose_at(pulse.time_s), scenario.mount, scenario.scan.model);
      const Eigen::Vector3d direction =
          ray_direction_enu(placement, pulse.alpha_deg, pulse.beta_deg);
      for (int r = 0; r < 2; ++r) {
        if (counts[r] >= counter.timeout_counts) continue;
        slots[2 * j + static_cast<std::size_t>(r)] =
            placement.origin_enu_m + range_from_counter(counts[r], counter) * direction;
      }
    }
  });
  out.clear();
  for (const Eigen::Vector3d& p : slots) {
    if (!std::isnan(p.x())) out.push_back(p);
  }
}

DetectionReport detect_recording(RecordingDecoder& decoder, const PoseSource& poses,
                                 const Scenario& scenario, const std::filesystem::path& csv,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  const ScanParams& scan = decoder.scan();
  ObstacleDetector detector(scenario.detector,
                            static_cast<double>(scan.pulses_per_frame()) / scan.prf_hz);
  AtomicOutputFile file(csv);
  std::string text(kDetectionsCsvHeader);
  DetectionReport report;
  std::set<std::int64_t> tracks;
  DecodedFrame frame;
  std::vector<Eigen::Vector3d> returns;
  while (decoder.next(frame)) {
    ++report.frames;
    report.pulses += frame.size();
    decoded_returns_enu(frame, poses, scenario, returns);
    report.returns += returns.size();
    DetectorFrame input;
    input.frame = frame.frame;
    input.time_s = frame.sweep.start_s;
    input.aircraft_enu_m = poses.pose_at(input.time_s).position_enu_m;
    input.returns_enu_m = returns;
    const std::span<const ObstacleWarning> warnings = detector.add_frame(input);
    report.warnings += warnings.size();
    for (const ObstacleWarning& warning : warnings) tracks.insert(warning.track);
    append_detection_rows(warnings, text);
    if (text.size() >= kFlushChars) {
      file.write(text);
      text.clear();
    }
    if (on_frame) on_frame(report.frames, report.pulses);
  }
  file.write(text);
  file.commit();
  report.tracks = tracks.size();
  return report;
}

DetectionReport detect_word_file(const Scenario& scenario, const std::filesystem::path& words,
                                 const std::filesystem::path& out_dir,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  RecordingDecoder decoder(words, scenario.scan);
  const LocalFrame local_frame(scenario.origin);
  const Trajectory trajectory = load_trajectory(scenario, local_frame);
  const RecordingLayout& layout = decoder.layout();
  if (layout.first_pulse_time_s < trajectory.start_s() ||
      layout.last_pulse_time_s > trajectory.end_s()) {
    throw input_error(words.string(), "its pulses lie outside the trajectory's time span: "
                                      "another flight's words, or another trajectory");
  }
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) {
    throw file_error(out_dir.string(), "cannot create the output folder: " + error.message());
  }
  return detect_recording(decoder, trajectory, scenario, out_dir / "detections.csv", on_frame);
}

DetectionReport detect_run_folder(const std::filesystem::path& run_dir,
                                  const std::filesystem::path& out_dir,
                                  const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  if (!std::filesystem::is_directory(run_dir)) {
    throw input_error(run_dir.string(), "not a folder");
  }
  const std::filesystem::path scenario_path = run_dir / "scenario.yaml";
  if (!std::filesystem::is_regular_file(scenario_path)) {
    throw input_error(run_dir.string(),
                      "not a run folder: it has no scenario.yaml (the scenario as flown, which "
                      "`owsim run` writes)");
  }
  const Scenario scenario = load_scenario(scenario_path);
  const std::filesystem::path words = run_dir / word_file_name(scenario.scan);
  if (!std::filesystem::is_regular_file(words)) {
    throw input_error(words.string(),
                      "missing: the detector reads the run's words (`owsim run` output d64)");
  }
  return detect_word_file(scenario, words, out_dir, on_frame);
}

}  // namespace owsim
