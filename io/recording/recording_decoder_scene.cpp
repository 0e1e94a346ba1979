#include "io/recording/recording_decoder_scene.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <sstream>

#include "geometry/error.hpp"
#include "io/recording/recording_check.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/mounting.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

// The east/north extent the recording's pulses can reach: the aircraft at every frame start and at
// the last pulse, widened by the counter's timeout range.
Eigen::AlignedBox2d recording_reach(const Trajectory& trajectory, const Scenario& scenario,
                                    const RecordingLayout& layout) {
  Eigen::AlignedBox2d box;
  for (std::int64_t f = layout.first_frame; f <= layout.last_frame; ++f) {
    const double t = layout.pulse_time_s(scenario.scan, f,
                                         f == layout.first_frame ? layout.first_pulse_in_frame : 0);
    box.extend(trajectory.pose_at(t).position_enu_m.head<2>());
  }
  box.extend(trajectory.pose_at(layout.last_pulse_time_s).position_enu_m.head<2>());
  const double max_range = timeout_range_m(scenario.receiver.counter);
  box.min().array() -= max_range;
  box.max().array() += max_range;
  return box;
}

std::string seconds(double value) {
  std::ostringstream text;
  text.precision(9);
  text << value;
  return text.str();
}

}  // namespace

Scenario load_recording_scenario(const std::filesystem::path& scenario_path,
                                 const RecordingScenarioOverrides& overrides) {
  Scenario scenario = load_scenario(scenario_path);
  if (overrides.trajectory) {
    const std::filesystem::path& file = *overrides.trajectory;
    const std::string format = overrides.trajectory_format
                                   ? *overrides.trajectory_format
                                   : (file.extension() == ".csv" ? "csv" : "hellsim");
    if (format != "hellsim" && format != "csv" && format != "sbet") {
      throw input_error("--trajectory-format",
                        "unknown trajectory format '" + format + "' (expected hellsim, csv, sbet)");
    }
    scenario.trajectory.source = TrajectorySpec::Source::file;
    scenario.trajectory.file = file;
    scenario.trajectory.format = format;
  } else if (overrides.trajectory_format) {
    throw input_error("--trajectory-format", "applies only with --trajectory");
  }
  if (overrides.seed) scenario.seed = *overrides.seed;
  if (overrides.no_noise) {
    scenario.receiver.range_noise_sigma_m = 0.0;
    scenario.receiver.noise.on = false;
  }
  return scenario;
}

void check_recording_format(const std::filesystem::path& recording,
                            const std::optional<std::string>& format, const Scenario& scenario) {
  std::optional<SensorModel> model;
  if (format) {
    model = parse_recording_format(*format);
    if (!model) {
      throw input_error("--format",
                        "unknown recording format '" + *format + "' (expected d64 or hellas)");
    }
  } else {
    model = recording_model_from_extension(recording);
  }
  if (model && *model != scenario.scan.model) {
    throw input_error(recording.string(), "is a " + std::string(recording_format_name(*model)) +
                                              " recording, but the scenario " +
                                              scenario.path.string() + " has sensor.model " +
                                              std::string(to_string(scenario.scan.model)));
  }
}

RecordingScene::RecordingScene(const Scenario& scenario, const RecordingLayout& layout)
    : local_frame_(scenario.origin),
      trajectory_(load_trajectory(scenario, local_frame_)),
      scene_(build_scene(scenario)) {
  if (layout.first_pulse_time_s < trajectory_.start_s() ||
      layout.last_pulse_time_s > trajectory_.end_s()) {
    throw input_error(layout.check.path.string(),
                      "its pulses run from " + seconds(layout.first_pulse_time_s) + " s to " +
                          seconds(layout.last_pulse_time_s) + " s, outside the trajectory (" +
                          seconds(trajectory_.start_s()) + " s to " + seconds(trajectory_.end_s()) +
                          " s): another trajectory, or the wrong wrap of the time tags (they fix "
                          "the time only modulo it: give the recording's start time, --start-s)");
  }
  embree_scene_ = std::make_unique<EmbreeScene>(device_, scene_, scenario.receiver,
                                                recording_reach(trajectory_, scenario, layout),
                                                timeout_range_m(scenario.receiver.counter));
}

std::vector<std::string> RecordingScene::object_ids() const { return owsim::object_ids(scene_); }

void pulse_rays(std::span<const Pulse> pulses, const PoseSource& poses, const Mount& mount,
                SensorModel model, std::vector<PulseRay>& rays, std::vector<std::uint8_t>& active) {
  rays.resize(pulses.size());
  active.resize(pulses.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pulses.size(), 512), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const Pulse& pulse = pulses[i];
      if (pulse.reference) {
        active[i] = 0;
        rays[i] = PulseRay{};
        continue;
      }
      const SensorPlacement placement = sensor_placement(poses.pose_at(pulse.time_s), mount, model);
      active[i] = 1;
      rays[i] = PulseRay{placement.origin_enu_m,
                         ray_direction_enu(placement, pulse.alpha_deg, pulse.beta_deg)};
    }
  });
}

}  // namespace owsim
