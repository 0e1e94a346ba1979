#include "detection/obstacle_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "detection/plan_cells.hpp"

namespace owsim {
namespace {

constexpr std::size_t kSample = 16;
constexpr double kVoxelM = 1.0;

std::uint64_t voxel_key(const Eigen::Vector3d& p) {
  const auto part = [](double v) {
    return static_cast<std::uint64_t>(cell_index(v, kVoxelM) + (std::int64_t{1} << 20)) &
           0x1FFFFFu;
  };
  return (part(p.x()) << 42) | (part(p.y()) << 21) | part(p.z());
}

bool is_wire(ObstacleClass kind) { return kind == ObstacleClass::wire; }

// How far an obstacle's point lies from a track (what association averages). A solid: the distance
// to the nearest remembered point. A wire: across the track's line in plan and in height from the
// remembered point nearest along it, so a piece of a conductor seen for the first time continues
// the conductor's track; `along_slack` (returned) is that point's distance along the line, which
// widens the tolerance (a catenary rises away from where it was seen).
struct Miss {
  double distance_m;
  double along_m;
};

// A point's place along a track's line from its centre, and its distance across it, in plan.
double along_line_m(const ObstacleTrack& track, const Eigen::Vector3d& p) {
  return (p.head<2>() - track.centre).dot(track.extent.axis);
}
double across_line_m(const ObstacleTrack& track, const Eigen::Vector3d& p) {
  const Eigen::Vector2d d = p.head<2>() - track.centre;
  return std::abs(d.x() * track.extent.axis.y() - d.y() * track.extent.axis.x());
}

// Whether a point may lie within `near` of a wire track (miss_of's distance within 2 × band + 10 %
// of its distance along the line): no farther across the line than that tolerance at the farthest
// the nearest remembered point can lie along it (the nearer end of the track's span). A bound by a
// hair wide, so that no point miss_of calls near is ever ruled out.
bool may_be_near_wire(const ObstacleTrack& track, const Eigen::Vector3d& p, double band_m) {
  const double s = along_line_m(track, p);
  const double farthest = std::min(std::abs(s - track.along_lo_m), std::abs(s - track.along_hi_m));
  return across_line_m(track, p) <= (2.0 * band_m + 0.1 * farthest) * (1.0 + 1e-9) + 1e-9;
}

Miss miss_of(const ObstacleTrack& track, const Eigen::Vector3d& p) {
  if (!is_wire(track.kind)) {
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& r : track.remembered) best = std::min(best, (r - p).squaredNorm());
    return {std::sqrt(best), 0.0};
  }
  const double s = along_line_m(track, p);
  const double across = across_line_m(track, p);
  const Eigen::Vector3d* nearest = nullptr;
  double nearest_ds = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& r : track.remembered) {
    const double ds = std::abs(along_line_m(track, r) - s);
    if (ds < nearest_ds) {
      nearest_ds = ds;
      nearest = &r;
    }
  }
  return {std::hypot(across, p.z() - nearest->z()), nearest_ds};
}

struct Pair {
  double mean_m;
  std::size_t track, obstacle;
};

}  // namespace

void ObstacleTracks::support(ObstacleTrack& track, const FrameObstacle& obstacle, double time_s) {
  track.kind = obstacle.kind;
  track.isolation_m = obstacle.isolation_m;
  track.last_support_s = time_s;
  track.points_now = static_cast<std::uint32_t>(obstacle.points.size());
  track.base_u_m =
      track.remembered.empty() ? obstacle.base_u_m : std::min(track.base_u_m, obstacle.base_u_m);
  for (const Eigen::Vector3d& p : obstacle.points) remember(track, p);
}

void ObstacleTracks::remember(ObstacleTrack& track, const Eigen::Vector3d& p) {
  if (track.remembered.size() >= kMaxRememberedPoints) return;
  if (!track.voxels.insert(voxel_key(p)).second) return;
  if (track.remembered.empty()) {
    track.lo = track.hi = p;
  } else {
    track.lo = track.lo.cwiseMin(p);
    track.hi = track.hi.cwiseMax(p);
  }
  track.remembered.push_back(p);
}

void ObstacleTracks::refresh_extent(ObstacleTrack& track) {
  if (track.extent_points == track.remembered.size()) return;
  track.extent = plan_extent(track.remembered);
  track.centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& r : track.remembered) track.centre += r.head<2>();
  track.centre /= static_cast<double>(track.remembered.size());
  track.along_lo_m = std::numeric_limits<double>::infinity();
  track.along_hi_m = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& r : track.remembered) {
    const double s = along_line_m(track, r);
    track.along_lo_m = std::min(track.along_lo_m, s);
    track.along_hi_m = std::max(track.along_hi_m, s);
  }
  track.extent_points = track.remembered.size();
}

void ObstacleTracks::classify_remembered(ObstacleTrack& track) const {
  if (is_wire(track.kind) || track.remembered.empty()) return;
  ObstacleShape shape;
  shape.length_m = track.extent.length_m;
  shape.width_m = track.extent.width_m;
  shape.height_m = track.hi.z() - track.base_u_m;
  shape.isolation_m = track.isolation_m;
  const ObstacleClass kind = solid_class(shape, params_);
  if (kind != ObstacleClass::none) track.kind = kind;
}

void ObstacleTracks::update(std::span<const FrameObstacle> obstacles, double time_s,
                            const Eigen::Vector3d& aircraft_enu_m) {
  for (ObstacleTrack& track : tracks_) track.points_now = 0;
  std::vector<Pair> pairs;
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    const FrameObstacle& obstacle = obstacles[o];
    if (obstacle.points.empty()) continue;
    Eigen::Vector3d lo = obstacle.points.front(), hi = lo;
    double range = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : obstacle.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
      range = std::min(range, (p - aircraft_enu_m).norm());
    }
    const double reach = 2.0 + 0.01 * range;
    const std::size_t step = std::max<std::size_t>(1, obstacle.points.size() / kSample);
    for (std::size_t t = 0; t < tracks_.size(); ++t) {
      const ObstacleTrack& track = tracks_[t];
      const bool wire = is_wire(track.kind);
      if (wire != is_wire(obstacle.kind)) continue;
      if (!wire && ((lo.array() - reach > track.hi.array()).any() ||
                    (hi.array() + reach < track.lo.array()).any())) {
        continue;
      }
      if (wire) {  // a track that cannot have half of the sample near is passed over
        std::size_t may = 0, samples = 0;
        for (std::size_t k = 0; k < obstacle.points.size(); k += step, ++samples) {
          may += may_be_near_wire(track, obstacle.points[k], params_.wire_band_m) ? 1 : 0;
        }
        if (2 * may < samples) continue;
      }
      double sum = 0.0;
      std::size_t near = 0, sampled = 0;
      for (std::size_t k = 0; k < obstacle.points.size(); k += step) {
        const Miss miss = miss_of(track, obstacle.points[k]);
        sum += miss.distance_m;
        const double within = wire ? 2.0 * params_.wire_band_m + 0.1 * miss.along_m : reach;
        near += miss.distance_m <= within ? 1 : 0;
        ++sampled;
      }
      if (2 * near >= sampled) pairs.push_back({sum / static_cast<double>(sampled), t, o});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [&](const Pair& a, const Pair& b) {
    return std::tie(a.mean_m, tracks_[a.track].id, a.obstacle) <
           std::tie(b.mean_m, tracks_[b.track].id, b.obstacle);
  });
  std::vector<std::uint8_t> track_taken(tracks_.size(), 0), obstacle_taken(obstacles.size(), 0);
  std::vector<std::size_t> taken_by(obstacles.size(), 0);
  for (const Pair& pair : pairs) {
    if (track_taken[pair.track] || obstacle_taken[pair.obstacle]) continue;
    track_taken[pair.track] = obstacle_taken[pair.obstacle] = 1;
    taken_by[pair.obstacle] = pair.track;
    support(tracks_[pair.track], obstacles[pair.obstacle], time_s);
  }
  // A track that this frame's obstacle also continues, but that another track took, is the same
  // obstacle seen in pieces before: it joins that track, which keeps the older id.
  std::vector<std::uint8_t> absorbed(tracks_.size(), 0);
  for (const Pair& pair : pairs) {
    if (track_taken[pair.track] || absorbed[pair.track] || !obstacle_taken[pair.obstacle]) continue;
    ObstacleTrack& from = tracks_[pair.track];
    ObstacleTrack& into = tracks_[taken_by[pair.obstacle]];
    into.id = std::min(into.id, from.id);
    into.base_u_m = std::min(into.base_u_m, from.base_u_m);
    for (const Eigen::Vector3d& p : from.remembered) remember(into, p);
    absorbed[pair.track] = 1;
  }
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    if (obstacle_taken[o] || obstacles[o].points.empty()) continue;
    ObstacleTrack track;
    track.id = next_id_++;
    support(track, obstacles[o], time_s);
    tracks_.push_back(std::move(track));
  }
  absorbed.resize(tracks_.size(), 0);  // the new tracks are kept
  for (std::size_t t = 0; t < tracks_.size(); ++t) {
    if (absorbed[t]) continue;
    refresh_extent(tracks_[t]);
    if (tracks_[t].points_now > 0) classify_remembered(tracks_[t]);
  }
  std::size_t kept = 0;
  for (std::size_t t = 0; t < tracks_.size(); ++t) {
    if (absorbed[t] || time_s - tracks_[t].last_support_s > params_.hold_s) continue;
    if (kept != t) tracks_[kept] = std::move(tracks_[t]);
    ++kept;
  }
  tracks_.resize(kept);
  // By id: a track that took an older one's id moves to its place.
  std::sort(tracks_.begin(), tracks_.end(),
            [](const ObstacleTrack& a, const ObstacleTrack& b) { return a.id < b.id; });
}

}  // namespace owsim
