#include "io/detections/recording_detections.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <string>
#include <system_error>

#include "geometry/error.hpp"
#include "io/run/output_kind.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/mounting.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
void decoded_returns_enu(const DecodedFrame& frame, const PoseSource& poses,
                         const Scenario& scenario, std::vector<Eigen::Vector3d>& out) {
  const RangeCounterParams& counter = scenario.receiver.counter;
  const Eigen::Matrix3d body_from_src =
      mount_rotation(scenario.mount) * model_rotation(scenario.scan.model);
  const int per_line = scenario.scan.fibers_per_line;
  const double line_s = per_line / scenario.scan.prf_hz;
  // The frame's lines: runs of pulses with one line index (a partial first or last line too).
  std::vector<std::size_t> line_starts;
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (j == 0 || frame.pulses[j].line != frame.pulses[j - 1].line) line_starts.push_back(j);
  }
  line_starts.push_back(frame.size());
  // sin α and cos α by slot, once a frame.
  std::vector<std::pair<double, double>> alpha_trig(static_cast<std::size_t>(per_line));
  std::vector<std::uint8_t> alpha_known(static_cast<std::size_t>(per_line), 0);
  for (const Pulse& pulse : frame.pulses) {
    const auto slot = static_cast<std::size_t>(pulse.slot);
    if (pulse.reference || alpha_known[slot]) continue;
    alpha_trig[slot] = alpha_sin_cos(pulse.alpha_deg);
    alpha_known[slot] = 1;
  }
  // Where each line's returns begin in `out` (pulse order, a pulse's first return first): a
  // pulse of the reference fiber has none, another one for each counter short of the timeout.
  const auto returns_of = [&](std::size_t j) -> std::size_t {
    if (frame.pulses[j].reference) return 0;
    return (frame.counter1[j] < counter.timeout_counts ? 1 : 0) +
           (frame.counter2[j] < counter.timeout_counts ? 1 : 0);
  };
  const auto line_count = line_starts.size() - 1;
  std::vector<std::size_t> line_first(line_count + 1, 0);
  for (std::size_t l = 0; l < line_count; ++l) {
    line_first[l + 1] = line_first[l];
    for (std::size_t j = line_starts[l]; j < line_starts[l + 1]; ++j)
      line_first[l + 1] += returns_of(j);
  }
  out.resize(line_first[line_count]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, line_count, 8), [&](const auto& range) {
    for (std::size_t l = range.begin(); l < range.end(); ++l) {
      const Pulse& first = frame.pulses[line_starts[l]];
      // The placement at the line's first slot and at the next line's, blended by slot.
      const double t0 = first.time_s - first.slot / scenario.scan.prf_hz;
      const SensorPlacement p0 =
          sensor_placement(poses.pose_at(t0), body_from_src, scenario.mount.lever_arm_m);
      const SensorPlacement p1 =
          sensor_placement(poses.pose_at(t0 + line_s), body_from_src, scenario.mount.lever_arm_m);
      std::size_t at = line_first[l];
      for (std::size_t j = line_starts[l]; j < line_starts[l + 1]; ++j) {
        const Pulse& pulse = frame.pulses[j];
        const std::uint16_t counts[2] = {frame.counter1[j], frame.counter2[j]};
        if (pulse.reference ||
            (counts[0] >= counter.timeout_counts && counts[1] >= counter.timeout_counts)) {
          continue;
        }
        const double s = static_cast<double>(pulse.slot) / per_line;
        const Eigen::Matrix3d enu_from_src = (1.0 - s) * p0.enu_from_src + s * p1.enu_from_src;
        const Eigen::Vector3d origin = (1.0 - s) * p0.origin_enu_m + s * p1.origin_enu_m;
        const auto [sin_alpha, cos_alpha] = alpha_trig[static_cast<std::size_t>(pulse.slot)];
        const Eigen::Vector3d direction =
            (enu_from_src * src_from_arc(arc_unit_ray(sin_alpha, cos_alpha, pulse.beta_deg)))
                .normalized();
        for (int r = 0; r < 2; ++r) {
          if (counts[r] >= counter.timeout_counts) continue;
          out[at++] = origin + range_from_counter(counts[r], counter) * direction;
        }
      }
    }
  });
  // A return placed at NaN (a pose that is none) is no return.
  std::erase_if(out, [](const Eigen::Vector3d& p) { return std::isnan(p.x()); });
}

DetectionReport detect_recording(
    RecordingDecoder& decoder, const PoseSource& poses, const Scenario& scenario,
    const std::filesystem::path& csv,
    const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  FlightDetections detections(scenario, poses, csv);
  detections.add_recording(decoder, std::numeric_limits<std::int64_t>::max(), on_frame);
  detections.finish();
  return detections.report();
}

DetectionReport detect_word_file(
    const Scenario& scenario, const std::filesystem::path& words, const std::filesystem::path& csv,
    const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  RecordingDecoder decoder(words, scenario.scan);
  const LocalFrame local_frame(scenario.origin);
  const Trajectory trajectory = load_trajectory(scenario, local_frame);
  const RecordingLayout& layout = decoder.layout();
  if (layout.first_pulse_time_s < trajectory.start_s() ||
      layout.last_pulse_time_s > trajectory.end_s()) {
    throw input_error(words.string(),
                      "its pulses lie outside the trajectory's time span: "
                      "another flight's words, or another trajectory");
  }
  const std::filesystem::path folder = csv.parent_path().empty() ? "." : csv.parent_path();
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) {
    throw file_error(folder.string(), "cannot create the output folder: " + error.message());
  }
  return detect_recording(decoder, trajectory, scenario, csv, on_frame);
}

RunRecording run_recording(const std::filesystem::path& run_dir) {
  if (!std::filesystem::is_directory(run_dir)) {
    throw input_error(run_dir.string(), "not a folder");
  }
  const std::filesystem::path scenario_path = run_dir / "scenario.yaml";
  if (!std::filesystem::is_regular_file(scenario_path)) {
    throw input_error(run_dir.string(),
                      "not a run folder: it has no scenario.yaml (the scenario as flown, which "
                      "`owsim run` writes)");
  }
  Scenario scenario = load_scenario(scenario_path);
  std::filesystem::path words = run_dir / word_file_name(scenario.scan);
  if (!std::filesystem::is_regular_file(words)) {
    throw input_error(words.string(),
                      "missing: the detector reads the run's words (`owsim run` output d64)");
  }
  return {std::move(scenario), std::move(words)};
}

DetectionReport detect_run_folder(
    const std::filesystem::path& run_dir, const std::filesystem::path& csv,
    const std::function<void(std::uint64_t, std::uint64_t)>& on_frame) {
  const RunRecording recording = run_recording(run_dir);
  return detect_word_file(recording.scenario, recording.words, csv, on_frame);
}

}  // namespace owsim
