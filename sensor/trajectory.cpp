#include "sensor/trajectory.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {
namespace {

std::string record_name(std::size_t index) { return "trajectory record " + std::to_string(index); }

void require_finite(double value, std::size_t index, const char* what) {
  if (!std::isfinite(value)) {
    throw input_error(record_name(index), std::string(what) + " is " + number_text(value, 10));
  }
}

void validate_track(const NavTrack& track) {
  const std::size_t n = track.time_s.size();
  if (track.position_enu_m.size() != n || track.attitude.size() != n) {
    throw Error("trajectory: the track's time, position and attitude arrays differ in length");
  }
  if (n < 2) {
    throw Error("trajectory: needs at least two records, got " + std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    require_finite(track.time_s[i], i, "time");
    require_finite(track.position_enu_m[i].x(), i, "east position");
    require_finite(track.position_enu_m[i].y(), i, "north position");
    require_finite(track.position_enu_m[i].z(), i, "up position");
    require_finite(track.attitude[i].roll_deg, i, "roll");
    require_finite(track.attitude[i].pitch_deg, i, "pitch");
    require_finite(track.attitude[i].heading_deg, i, "heading");
    if (i > 0 && !(track.time_s[i] > track.time_s[i - 1])) {
      throw input_error(record_name(i), "time " + number_text(track.time_s[i], 10) +
                                            " s is not after the previous record's " +
                                            number_text(track.time_s[i - 1], 10) + " s");
    }
  }
}

}  // namespace

double wrap_360_deg(double angle_deg) {
  double wrapped = std::fmod(angle_deg, 360.0);
  if (wrapped < 0.0) wrapped += 360.0;
  return wrapped >= 360.0 ? 0.0 : wrapped;  // −1e-17 + 360 rounds to 360
}

double wrap_180_deg(double angle_deg) {
  const double wrapped = wrap_360_deg(angle_deg);
  return wrapped > 180.0 ? wrapped - 360.0 : wrapped;
}

std::vector<double> unwrap_deg(const std::vector<double>& angles_deg) {
  std::vector<double> unwrapped(angles_deg.size());
  for (std::size_t i = 0; i < angles_deg.size(); ++i) {
    if (i == 0) {
      unwrapped[i] = angles_deg[i];
      continue;
    }
    double step = wrap_360_deg(angles_deg[i] - angles_deg[i - 1]);  // [0, 360)
    if (step >= 180.0) step -= 360.0;                               // [−180, 180)
    unwrapped[i] = unwrapped[i - 1] + step;
  }
  return unwrapped;
}

Trajectory::Trajectory(const NavTrack& track, const LocalFrame& frame,
                       const TrajectoryOptions& options) {
  validate_track(track);
  validate_smoothing(options.smoothing, "trajectory smoothing");
  if (!std::isfinite(options.magnetic_variation_deg)) {
    throw Error("trajectory: magnetic variation is not finite");
  }
  const std::size_t n = track.time_s.size();
  std::vector<double> east(n), north(n), up(n), roll(n), pitch(n), heading(n);
  for (std::size_t i = 0; i < n; ++i) {
    east[i] = track.position_enu_m[i].x();
    north[i] = track.position_enu_m[i].y();
    up[i] = track.position_enu_m[i].z();
    roll[i] = track.attitude[i].roll_deg;
    pitch[i] = track.attitude[i].pitch_deg;
    heading[i] = track.attitude[i].heading_deg;
  }
  heading = unwrap_deg(heading);
  roll = unwrap_deg(roll);
  if (options.heading_magnetic) {
    for (double& value : heading) value += options.magnetic_variation_deg;  // SENSOR-SPEC §5
  }
  std::vector<double>* channels[] = {&east, &north, &up, &roll, &pitch, &heading};
  savitzky_golay_in_place(track.time_s, channels, options.smoothing);
  if (options.irs_noise) {
    std::vector<Attitude> attitudes(n);
    for (std::size_t i = 0; i < n; ++i) attitudes[i] = {roll[i], pitch[i], heading[i]};
    add_irs_attitude_error(options.irs, options.seed, attitudes);
    for (std::size_t i = 0; i < n; ++i) {
      roll[i] = attitudes[i].roll_deg;
      pitch[i] = attitudes[i].pitch_deg;
      heading[i] = attitudes[i].heading_deg;
    }
  }
  frame_from_local_enu_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Quaterniond rotation(
        frame.enu_rotation_at(Eigen::Vector3d(east[i], north[i], up[i])));
    frame_from_local_enu_.push_back(rotation.normalized());
  }
  east_ = CubicSpline(track.time_s, std::move(east));
  north_ = CubicSpline(track.time_s, std::move(north));
  up_ = CubicSpline(track.time_s, std::move(up));
  roll_ = CubicSpline(track.time_s, std::move(roll));
  pitch_ = CubicSpline(track.time_s, std::move(pitch));
  heading_ = CubicSpline(track.time_s, std::move(heading));
}

Eigen::Matrix3d Trajectory::frame_rotation_in(std::size_t interval, double time_s) const {
  const std::vector<double>& t = heading_.knots_x();
  double s = (time_s - t[interval]) / (t[interval + 1] - t[interval]);
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  const Eigen::Quaterniond& a = frame_from_local_enu_[interval];
  Eigen::Quaterniond b = frame_from_local_enu_[interval + 1];
  if (a.dot(b) < 0.0) b.coeffs() = -b.coeffs();  // the same rotation, the nearer sign
  Eigen::Quaterniond blend;
  blend.coeffs() = (1.0 - s) * a.coeffs() + s * b.coeffs();
  return blend.normalized().toRotationMatrix();
}

Pose Trajectory::pose_at(double time_s) const {
  const std::size_t i = heading_.interval(time_s);  // all six splines share the knots
  Pose pose;
  pose.time_s = time_s;
  pose.position_enu_m = {east_.value_in(i, time_s), north_.value_in(i, time_s),
                         up_.value_in(i, time_s)};
  pose.attitude.roll_deg = wrap_180_deg(roll_.value_in(i, time_s));
  pose.attitude.pitch_deg = pitch_.value_in(i, time_s);
  pose.attitude.heading_deg = wrap_360_deg(heading_.value_in(i, time_s));
  pose.frame_from_local_enu = frame_rotation_in(i, time_s);
  return pose;
}

double Trajectory::heading_rate_deg_per_s(double time_s) const {
  return heading_.derivative(time_s);
}

std::vector<Pose> Trajectory::knots() const {
  const std::vector<double>& t = heading_.knots_x();
  std::vector<Pose> knots(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    Pose& pose = knots[i];
    pose.time_s = t[i];
    pose.position_enu_m = {east_.knots_y()[i], north_.knots_y()[i], up_.knots_y()[i]};
    pose.attitude = {wrap_180_deg(roll_.knots_y()[i]), pitch_.knots_y()[i],
                     wrap_360_deg(heading_.knots_y()[i])};
    pose.frame_from_local_enu = frame_from_local_enu_[i].toRotationMatrix();
  }
  return knots;
}

}  // namespace owsim
