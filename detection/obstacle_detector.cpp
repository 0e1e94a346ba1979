#include "detection/obstacle_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detection/median.hpp"
#include "detection/plan_cells.hpp"
#include "geometry/error.hpp"

namespace owsim {
namespace {

// Plan cells of a point set, for "is any of them within r of here" (cells of r).
class PlanNeighbours {
 public:
  PlanNeighbours(std::span<const ObstaclePoint> points, std::span<const std::uint32_t> members,
                 double r)
      : points_(points), r_(r) {
    for (const std::uint32_t p : members) entries_.push_back({key(points[p].enu_m), p});
    std::vector<CellPoint> buffer;
    sort_by_cell(entries_, buffer);
  }
  [[nodiscard]] bool any_within(const Eigen::Vector3d& at) const {
    const auto [i, j] = cell(at);
    for (std::int64_t di = -1; di <= 1; ++di) {
      // Cells (i + di, j − 1 … j + 1) have consecutive keys.
      const std::uint64_t first = plan_cell_key(i + di, j - 1);
      auto it = std::lower_bound(
          entries_.begin(), entries_.end(), first,
          [](const CellPoint& entry, std::uint64_t key) { return entry.key < key; });
      for (; it != entries_.end() && it->key <= first + 2; ++it) {
        if ((points_[it->point].enu_m.head<2>() - at.head<2>()).norm() <= r_) return true;
      }
    }
    return false;
  }

 private:
  [[nodiscard]] std::pair<std::int64_t, std::int64_t> cell(const Eigen::Vector3d& p) const {
    return {cell_index(p.x(), r_), cell_index(p.y(), r_)};
  }
  [[nodiscard]] std::uint64_t key(const Eigen::Vector3d& p) const {
    return plan_cell_key(p.x(), p.y(), r_);
  }
  std::span<const ObstaclePoint> points_;
  double r_;
  std::vector<CellPoint> entries_;  // by cell (within a cell, in no order that matters)
};

// Whether a cluster of at least min_points points may hold a piece of a wire: 15 m long or more
// (a tree's crown, a pole, a house are less), or at least 4 m and three times as long as it is
// wide. Compact clusters are not searched for lines; smaller groups (a far wire's scattered hits)
// always are.
bool may_hold_a_wire(const PlanExtent& extent) {
  constexpr double kCompactM = 15.0;
  return extent.length_m >= kCompactM ||
         (extent.length_m >= 4.0 && extent.length_m > 3.0 * extent.width_m);
}

struct Box {
  Eigen::Vector2d lo, hi;
};

Box plan_box(std::span<const ObstaclePoint> points, std::span<const std::uint32_t> members) {
  Box box{points[members.front()].enu_m.head<2>(), points[members.front()].enu_m.head<2>()};
  for (const std::uint32_t p : members) {
    box.lo = box.lo.cwiseMin(points[p].enu_m.head<2>());
    box.hi = box.hi.cwiseMax(points[p].enu_m.head<2>());
  }
  return box;
}

// The lowest visible ground under a set of points (each point's own estimate).
double ground_under(std::span<const ObstaclePoint> points, std::span<const std::uint32_t> members) {
  double ground = std::numeric_limits<double>::infinity();
  for (const std::uint32_t p : members) ground = std::min(ground, points[p].ground_u_m);
  return ground;
}

}  // namespace

ObstacleDetector::ObstacleDetector(const DetectorParams& params, double frame_period_s)
    : params_(params),
      window_frames_(1),
      ground_(std::max(params.ground_cell_m, 0.5), std::min(params.max_range_m, 100000.0)),
      tracks_(params) {
  const std::vector<std::string> problems = detector_param_problems(params);
  if (!problems.empty()) throw input_error("detector", problems.front());
  if (!(frame_period_s > 0.0) || !std::isfinite(frame_period_s)) {
    throw Error("detector: the frame period must be a positive number of seconds");
  }
  window_frames_ = static_cast<std::size_t>(
      std::max(1.0, std::floor(params.window_s / frame_period_s + 1e-9)));
}

std::span<const ObstacleWarning> ObstacleDetector::add_frame(const DetectorFrame& frame) {
  const Eigen::Vector3d& aircraft = frame.aircraft_enu_m;
  // 1. The ground, then the frame's elevated returns.
  // The returns within reach, with their ranges and ground cells (looked up again below).
  nearby_.clear();
  for (std::uint32_t k = 0; k < frame.returns_enu_m.size(); ++k) {
    const Eigen::Vector3d& p = frame.returns_enu_m[k];
    if (!p.allFinite()) continue;
    const double range = (p - aircraft).norm();
    if (range > params_.max_range_m) continue;
    const GroundMap::Place at = ground_.place_of(p.x(), p.y());
    ground_.add(at, p.z());
    nearby_.push_back({at, range, k});
  }
  std::vector<ObstaclePoint> elevated;
  for (const NearbyReturn& near : nearby_) {
    const Eigen::Vector3d& p = frame.returns_enu_m[near.index];
    // A point over ground not yet seen twice nearby has no visible height: not kept.
    const double ground = ground_.ground_u(near.cell);
    if (p.z() - ground >= params_.min_height_m) elevated.push_back({p, ground, near.range_m});
  }
  window_.push_back(std::move(elevated));
  while (window_.size() > window_frames_) window_.pop_front();

  // The window's points, their ground brought up to date (it only ever lowers).
  points_.clear();
  for (const std::vector<ObstaclePoint>& kept : window_) {
    for (const ObstaclePoint& p : kept) {
      ObstaclePoint q = p;
      q.ground_u_m = std::min(q.ground_u_m, ground_.ground_u(q.enu_m.x(), q.enu_m.y()));
      points_.push_back(q);
    }
  }
  classify(aircraft);
  tracks_.update(obstacles_, frame.time_s, aircraft);

  // 4. Every live track is a warning.
  warnings_.clear();
  for (const ObstacleTrack& track : tracks_.tracks()) {
    ObstacleWarning warning;
    warning.frame = frame.frame;
    warning.time_s = frame.time_s;
    warning.track = track.id;
    warning.kind = track.kind;
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : track.remembered) {
      const double d = (p - aircraft).squaredNorm();
      if (d < best) {
        best = d;
        warning.nearest_enu_m = p;
      }
    }
    warning.range_m = std::sqrt(best);
    warning.length_m = track.extent.length_m;
    warning.width_m = track.extent.width_m;
    warning.height_m = track.hi.z() - track.base_u_m;
    warning.points = track.points_now;
    warnings_.push_back(warning);
  }
  return warnings_;
}

void ObstacleDetector::classify(const Eigen::Vector3d& aircraft) {
  obstacles_.clear();
  const std::span<const ObstaclePoint> points(points_);
  // 2. Wire candidates among the points of clusters that may hold a wire (a tree, a pole or a
  // house alone holds none: the Hough transform need not see the wood), then the other points'
  // clusters (the wires' "other objects").
  std::vector<std::uint8_t> skip(points.size(), 0);
  find_clusters(points, skip, params_, cluster_scratch_, all_clusters_);
  std::vector<std::uint8_t> eligible(points.size(), 0);
  std::vector<Eigen::Vector3d> member_at;
  for (const PointCluster& cluster : all_clusters_) {
    if (cluster.points.size() >= static_cast<std::size_t>(params_.min_points)) {
      member_at.clear();
      for (const std::uint32_t p : cluster.points) member_at.push_back(points[p].enu_m);
      if (!may_hold_a_wire(plan_extent(member_at))) continue;
    }
    for (const std::uint32_t p : cluster.points) eligible[p] = 1;
  }
  find_wire_candidates(points, eligible, aircraft.head<2>(), params_, wire_scratch_, wires_);
  for (const WireCandidate& wire : wires_) {
    for (const std::uint32_t p : wire.points) skip[p] = 1;
  }
  find_clusters_without(points, skip, all_clusters_, params_, cluster_scratch_, clusters_);
  const auto least = static_cast<std::size_t>(params_.min_points);
  std::vector<std::uint32_t> others;
  for (const PointCluster& cluster : clusters_) {
    if (wires_.empty()) break;  // no wire to isolate
    if (cluster.points.size() >= least) {
      others.insert(others.end(), cluster.points.begin(), cluster.points.end());
    }
  }
  const PlanNeighbours neighbours(points, others, params_.wire_isolation_m);
  std::vector<std::uint8_t> accepted(wires_.size(), 0);
  bool any_rejected = false;
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    const WireCandidate& wire = wires_[w];
    ObstacleShape shape;
    shape.length_m = wire.length_m;
    shape.width_m = wire.width_m;
    std::size_t isolated = 0;
    std::vector<double> clearances;
    for (const std::uint32_t p : wire.points) {
      isolated += neighbours.any_within(points[p].enu_m) ? 0 : 1;
      clearances.push_back(points[p].enu_m.z() - points[p].ground_u_m);
    }
    shape.isolated_share =
        static_cast<double>(isolated) / static_cast<double>(wire.points.size());
    shape.clearance_m = median_of(clearances);
    accepted[w] = wire_rule(shape, params_) ? 1 : 0;
    any_rejected = any_rejected || !accepted[w];
  }
  // A rejected candidate's points belong to what stands around it (a roof's edge to its house).
  if (any_rejected) {
    std::fill(skip.begin(), skip.end(), 0);
    for (std::size_t w = 0; w < wires_.size(); ++w) {
      if (!accepted[w]) continue;
      for (const std::uint32_t p : wires_[w].points) skip[p] = 1;
    }
    find_clusters_without(points, skip, all_clusters_, params_, cluster_scratch_, clusters_);
  }
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    if (!accepted[w]) continue;
    FrameObstacle obstacle;
    obstacle.kind = ObstacleClass::wire;
    for (const std::uint32_t p : wires_[w].points) obstacle.points.push_back(points[p].enu_m);
    obstacle.base_u_m = ground_under(points, wires_[w].points);
    obstacles_.push_back(std::move(obstacle));
  }

  // 3. Solids: POLE, TREE or none.
  std::vector<const PointCluster*> solids;
  std::vector<Box> boxes;
  for (const PointCluster& cluster : clusters_) {
    if (cluster.points.size() < least) continue;
    solids.push_back(&cluster);
    boxes.push_back(plan_box(points, cluster.points));
  }
  std::vector<Box> wire_boxes;
  for (const WireCandidate& wire : wires_) wire_boxes.push_back(plan_box(points, wire.points));
  std::vector<Eigen::Vector3d> member_points;
  for (std::size_t c = 0; c < solids.size(); ++c) {
    const PointCluster& cluster = *solids[c];
    member_points.clear();
    double top = -std::numeric_limits<double>::infinity();
    double lowest = std::numeric_limits<double>::infinity();
    for (const std::uint32_t p : cluster.points) {
      member_points.push_back(points[p].enu_m);
      top = std::max(top, points[p].enu_m.z());
      lowest = std::min(lowest, points[p].enu_m.z());
    }
    const PlanExtent extent = plan_extent(member_points);
    ObstacleShape shape;
    shape.length_m = extent.length_m;
    shape.width_m = extent.width_m;
    const double ground = ground_under(points, cluster.points);
    const double base = lowest - ground <= params_.standing_within_m ? ground : lowest;
    shape.height_m = top - base;
    double isolation_squared = std::numeric_limits<double>::infinity();
    for (std::size_t o = 0; o < solids.size(); ++o) {
      if (o == c) continue;
      isolation_squared = std::min(isolation_squared, plan_gap_squared_m2(boxes[c].lo, boxes[c].hi,
                                                                          boxes[o].lo, boxes[o].hi));
    }
    for (std::size_t w = 0; w < wires_.size(); ++w) {
      if (!accepted[w]) continue;
      // No point of the wire is nearer than its plan box.
      if (plan_gap_squared_m2(boxes[c].lo, boxes[c].hi, wire_boxes[w].lo, wire_boxes[w].hi) >=
          isolation_squared) {
        continue;
      }
      for (const std::uint32_t p : wires_[w].points) {
        const Eigen::Vector2d wire_at = points[p].enu_m.head<2>();
        isolation_squared = std::min(
            isolation_squared, plan_gap_squared_m2(boxes[c].lo, boxes[c].hi, wire_at, wire_at));
      }
    }
    shape.isolation_m = std::sqrt(isolation_squared);
    const ObstacleClass kind = solid_class(shape, params_);
    if (kind == ObstacleClass::none) continue;
    FrameObstacle obstacle;
    obstacle.kind = kind;
    obstacle.points = member_points;
    obstacle.base_u_m = base;
    obstacle.isolation_m = shape.isolation_m;
    obstacles_.push_back(std::move(obstacle));
  }
}

}  // namespace owsim
