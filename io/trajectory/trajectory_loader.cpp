#include "io/trajectory/trajectory_loader.hpp"

#include "geometry/error.hpp"
#include "io/trajectory/ardupilot_log_reader.hpp"
#include "io/trajectory/hellsim_reader.hpp"
#include "io/trajectory/sbet_reader.hpp"
#include "io/trajectory/trajectory_csv_reader.hpp"
#include "sensor/waypoint_plan.hpp"

namespace owsim {

NavTrack load_nav_track(const Scenario& scenario, const LocalFrame& frame) {
  const TrajectorySpec& spec = scenario.trajectory;
  if (spec.source == TrajectorySpec::Source::waypoints) {
    WaypointPlan plan;
    plan.speed_mps = spec.speed_mps;
    plan.points_enu_m = spec.waypoints_enu_m;
    plan.max_bank_deg = spec.max_bank_deg;
    return waypoint_track(plan);
  }
  const std::string path = spec.file.string();
  if (spec.format == "hellsim") {
    HellSimOptions options;
    options.tick_s = spec.tick_s;
    return to_local(read_hellsim(path, options), frame);
  }
  if (spec.format == "csv") return to_local(read_trajectory_csv(path), frame);
  if (spec.format == "sbet") return to_local(read_sbet(path), frame);
  if (spec.format == "ardupilot") return to_local(read_ardupilot_log(path).records, frame);
  throw input_error(scenario.path.string() + ": trajectory.format",
                    "unknown trajectory format '" + spec.format + "'");
}

Trajectory load_trajectory(const Scenario& scenario, const LocalFrame& frame) {
  const TrajectorySpec& spec = scenario.trajectory;
  TrajectoryOptions options;
  if (spec.source == TrajectorySpec::Source::file) {
    options.smoothing = SmoothingParams{spec.smoothing_window, spec.smoothing_degree};
  } else {
    options.smoothing = SmoothingParams{1, 0};
  }
  options.heading_magnetic = spec.heading_magnetic;
  options.magnetic_variation_deg = spec.magnetic_variation_deg;
  options.irs_noise = spec.irs_noise;
  options.seed = scenario.seed;
  // A problem found after reading ("trajectory record 12: time …", a route too long) names where
  // the records came from: the trajectory file, or the scenario file that holds the waypoints.
  const std::string source =
      spec.source == TrajectorySpec::Source::file ? spec.file.string() : scenario.path.string();
  try {
    return Trajectory(load_nav_track(scenario, frame), frame, options);
  } catch (const FileError&) {
    throw;
  } catch (const Error& error) {
    const std::string message = error.what();
    if (source.empty() || message.starts_with(source)) throw;
    throw input_error(source, message);
  }
}

}  // namespace owsim
