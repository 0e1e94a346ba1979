#include "sensor/waypoint_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

std::string point_name(std::size_t index) {
  return "trajectory.waypoints.points[" + std::to_string(index) + "]";
}

// Horizontal unit vector (east, north) of a heading in radians.
Eigen::Vector2d forward(double heading_rad) {
  return {std::sin(heading_rad), std::cos(heading_rad)};
}
// Horizontal unit vector to the right of a heading.
Eigen::Vector2d right(double heading_rad) {
  return {std::cos(heading_rad), -std::sin(heading_rad)};
}

// One piece of the path: a straight line or a horizontal arc, with a constant climb per
// horizontal metre, flown at constant speed.
struct Segment {
  bool arc = false;
  double start_time_s = 0;
  double duration_s = 0;
  Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
  double heading_rad = 0;  // straight: the track; arc: the heading at its start
  double climb_per_m = 0;  // du / d(horizontal distance)
  double horizontal_length_m = 0;
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();  // arc only
  double turn_sign = 0;  // arc: +1 right (heading increasing), −1 left
  double bank_deg = 0;   // arc: signed, positive right wing down
};

double along_path_factor(double climb_per_m) { return std::sqrt(1.0 + climb_per_m * climb_per_m); }

Segment make_straight(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double speed_mps) {
  Segment segment;
  const Eigen::Vector2d horizontal = (to - from).head<2>();
  segment.start_m = from;
  segment.horizontal_length_m = horizontal.norm();
  segment.heading_rad = std::atan2(horizontal.x(), horizontal.y());
  segment.climb_per_m =
      segment.horizontal_length_m > 0 ? (to.z() - from.z()) / segment.horizontal_length_m : 0.0;
  segment.duration_s =
      segment.horizontal_length_m * along_path_factor(segment.climb_per_m) / speed_mps;
  return segment;
}

void validate_plan(const WaypointPlan& plan) {
  const std::string where = "trajectory.waypoints";
  if (!(std::isfinite(plan.speed_mps) && plan.speed_mps > 0)) {
    throw input_error(where, "speed " + number_text(plan.speed_mps, 6) + " m/s must be positive");
  }
  if (!(plan.max_bank_deg > 0 && plan.max_bank_deg < 90)) {
    throw input_error(where, "maximum bank " + number_text(plan.max_bank_deg, 6) +
                                 "° must lie between 0° and 90°");
  }
  if (!(std::isfinite(plan.sample_hz) && plan.sample_hz > 0)) {
    throw input_error(where,
                      "sample rate " + number_text(plan.sample_hz, 6) + " Hz must be positive");
  }
  if (!(std::isfinite(plan.roll_in_s) && plan.roll_in_s >= 0)) {
    throw input_error(where, "roll-in time " + number_text(plan.roll_in_s, 6) + " s must be ≥ 0");
  }
  if (plan.points_enu_m.size() < 2) {
    throw input_error(where,
                      "needs at least two points, got " + std::to_string(plan.points_enu_m.size()));
  }
  for (std::size_t i = 0; i < plan.points_enu_m.size(); ++i) {
    if (!plan.points_enu_m[i].allFinite())
      throw input_error(point_name(i), "position is not finite");
    if (i > 0 && (plan.points_enu_m[i] - plan.points_enu_m[i - 1]).head<2>().norm() < 1e-6) {
      throw input_error(point_name(i),
                        "has no horizontal distance from the previous point: a leg "
                        "needs a direction to fly");
    }
  }
}

// The path: straight legs shortened by the fillets, and the fillet arcs between them.
std::vector<Segment> build_path(const WaypointPlan& plan) {
  const std::vector<Eigen::Vector3d>& points = plan.points_enu_m;
  const std::size_t n = points.size();
  const double radius_m = turn_radius_m(plan.speed_mps, plan.max_bank_deg);

  std::vector<Segment> legs;  // the full legs, point i → i+1
  for (std::size_t i = 0; i + 1 < n; ++i)
    legs.push_back(make_straight(points[i], points[i + 1], plan.speed_mps));

  // Signed turn angle and tangent distance at every corner (0 at the ends).
  std::vector<double> turn_rad(n, 0.0), tangent_m(n, 0.0);
  for (std::size_t j = 1; j + 1 < n; ++j) {
    const double turn_deg =
        wrap_180_deg((legs[j].heading_rad - legs[j - 1].heading_rad) * kDegPerRad);
    if (std::abs(turn_deg) >= 180.0 - 1e-9) {
      throw input_error(point_name(j), "the route reverses here (a 180° turn has no fillet)");
    }
    turn_rad[j] = turn_deg / kDegPerRad;
    tangent_m[j] = radius_m * std::tan(std::abs(turn_rad[j]) / 2.0);
  }
  for (std::size_t j = 1; j + 1 < n; ++j) {
    const auto check_leg = [&](std::size_t leg, double needed_m) {
      if (needed_m > legs[leg].horizontal_length_m * (1.0 + 1e-12)) {
        throw input_error(
            point_name(j),
            "the " + number_text(std::abs(turn_rad[j]) * kDegPerRad, 6) + "° turn at radius " +
                number_text(radius_m, 6) + " m (speed " + number_text(plan.speed_mps, 6) +
                " m/s, bank " + number_text(plan.max_bank_deg, 6) + "°) needs " +
                number_text(needed_m, 6) + " m of the leg from point " + std::to_string(leg) +
                " to point " + std::to_string(leg + 1) + ", which is " +
                number_text(legs[leg].horizontal_length_m, 6) + " m long: the corner is too tight");
      }
    };
    check_leg(j - 1, tangent_m[j - 1] + tangent_m[j]);
    if (j + 2 == n) check_leg(j, tangent_m[j]);
  }

  std::vector<Segment> path;
  Eigen::Vector3d position = points[0];
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Segment& leg = legs[i];
    const Eigen::Vector2d direction = forward(leg.heading_rad);
    const double end_distance_m = leg.horizontal_length_m - tangent_m[i + 1];
    Eigen::Vector3d leg_end;
    leg_end << points[i].head<2>() + end_distance_m * direction,
        points[i].z() + end_distance_m * leg.climb_per_m;
    Segment straight = make_straight(position, leg_end, plan.speed_mps);
    straight.heading_rad = leg.heading_rad;  // also where the straight has shrunk to nothing
    straight.climb_per_m = leg.climb_per_m;
    path.push_back(straight);
    position = leg_end;
    if (i + 2 == n || turn_rad[i + 1] == 0.0) continue;

    const std::size_t j = i + 1;
    const Segment& next = legs[j];
    Segment arc;
    arc.arc = true;
    arc.start_m = position;
    arc.heading_rad = leg.heading_rad;
    arc.turn_sign = turn_rad[j] > 0 ? 1.0 : -1.0;
    arc.horizontal_length_m = radius_m * std::abs(turn_rad[j]);
    const double exit_height_m = points[j].z() + tangent_m[j] * next.climb_per_m;
    arc.climb_per_m = (exit_height_m - position.z()) / arc.horizontal_length_m;
    arc.centre_m = position.head<2>() + arc.turn_sign * radius_m * right(leg.heading_rad);
    arc.duration_s = arc.horizontal_length_m * along_path_factor(arc.climb_per_m) / plan.speed_mps;
    const double heading_rate_deg_per_s = arc.turn_sign * kDegPerRad * plan.speed_mps /
                                          (along_path_factor(arc.climb_per_m) * radius_m);
    arc.bank_deg = coordinated_bank_deg(plan.speed_mps, heading_rate_deg_per_s);
    path.push_back(arc);
    position << points[j].head<2>() + tangent_m[j] * forward(next.heading_rad), exit_height_m;
  }
  double time_s = 0.0;
  for (Segment& segment : path) {
    segment.start_time_s = time_s;
    time_s += segment.duration_s;
  }
  return path;
}

// Ramp weight in [0, 1]: 0 before centre − ramp/2, 1 after centre + ramp/2, linear between.
double ramp(double time_s, double centre_s, double ramp_s) {
  if (ramp_s <= 0) return time_s >= centre_s ? 1.0 : 0.0;
  return std::clamp((time_s - (centre_s - 0.5 * ramp_s)) / ramp_s, 0.0, 1.0);
}

// The bank at time_s: the sum of every turn's ramped bank. Only the turns whose roll-in or
// roll-out window (at most roll_in_s/2 either side of their ends) holds time_s add anything other
// than zero, so only those around path[current] (the segment flown at time_s) are visited, in
// path order, which keeps the sum bit for bit that of visiting every turn (a route of thousands
// of waypoints visited all of them for every sample: minutes for a few frames).
double roll_deg_at(const std::vector<Segment>& path, std::size_t current, double time_s,
                   double roll_in_s) {
  const double half_s = 0.5 * roll_in_s;
  std::size_t first = current, last = current;
  while (first > 0 &&
         path[first - 1].start_time_s + path[first - 1].duration_s + half_s >= time_s) {
    --first;
  }
  while (last + 1 < path.size() && path[last + 1].start_time_s - half_s <= time_s) ++last;
  double roll = 0.0;
  for (std::size_t i = first; i <= last; ++i) {
    const Segment& segment = path[i];
    if (!segment.arc) continue;
    const double ramp_s = std::min(roll_in_s, segment.duration_s);
    const double entry = ramp(time_s, segment.start_time_s, ramp_s);
    const double exit = ramp(time_s, segment.start_time_s + segment.duration_s, ramp_s);
    roll += segment.bank_deg * (entry - exit);
  }
  return roll;
}

}  // namespace

double turn_radius_m(double speed_mps, double bank_deg) {
  return speed_mps * speed_mps / (kStandardGravityMps2 * std::tan(bank_deg / kDegPerRad));
}

double coordinated_bank_deg(double speed_mps, double heading_rate_deg_per_s) {
  return kDegPerRad *
         std::atan(speed_mps * (heading_rate_deg_per_s / kDegPerRad) / kStandardGravityMps2);
}

NavTrack waypoint_track(const WaypointPlan& plan) {
  validate_plan(plan);
  const std::vector<Segment> path = build_path(plan);
  const double total_s = path.back().start_time_s + path.back().duration_s;
  // The track is sampled whole before the first frame: a route longer than a day (a crawl over
  // thousands of km) would hold more samples than memory, so it is refused.
  constexpr double kMaxRouteS = 86'400.0;
  if (!(total_s <= kMaxRouteS)) {
    throw input_error("trajectory.waypoints", "the route takes " + number_text(total_s, 6) +
                                                  " s at " + number_text(plan.speed_mps, 6) +
                                                  " m/s; owsim flies routes of up to " +
                                                  number_text(kMaxRouteS, 6) + " s");
  }
  const auto samples =
      static_cast<std::size_t>(std::max(1.0, std::ceil(total_s * plan.sample_hz - 1e-9)));

  NavTrack track;
  std::size_t current = 0;
  for (std::size_t k = 0; k <= samples; ++k) {
    const double time_s = k == samples ? total_s : total_s * double(k) / double(samples);
    while (current + 1 < path.size() && time_s >= path[current + 1].start_time_s) ++current;
    const Segment& segment = path[current];
    const double horizontal_m = std::clamp(
        (time_s - segment.start_time_s) * plan.speed_mps / along_path_factor(segment.climb_per_m),
        0.0, segment.horizontal_length_m);
    Eigen::Vector3d position;
    double heading_rad = segment.heading_rad;
    if (segment.arc) {
      const double radius_m = turn_radius_m(plan.speed_mps, plan.max_bank_deg);
      heading_rad += segment.turn_sign * horizontal_m / radius_m;
      position << segment.centre_m - segment.turn_sign * radius_m * right(heading_rad),
          segment.start_m.z() + segment.climb_per_m * horizontal_m;
    } else {
      position << segment.start_m.head<2>() + horizontal_m * forward(segment.heading_rad),
          segment.start_m.z() + segment.climb_per_m * horizontal_m;
    }
    track.time_s.push_back(time_s);
    track.position_enu_m.push_back(position);
    track.attitude.push_back({roll_deg_at(path, current, time_s, plan.roll_in_s),
                              kDegPerRad * std::atan(segment.climb_per_m),
                              wrap_360_deg(kDegPerRad * heading_rad)});
  }
  return track;
}

}  // namespace owsim
