#include "evaluation/frame_truth.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kVelocityStepS = 0.005;  // the central difference of the sensor's velocity

// Nearest point overall and nearest point in the field, over an object's segments given as
// sensor-frame offsets (SRC). The segments are kept (in a per-thread scratch buffer) so that the
// clip against the field visits them nearest first and stops as soon as no segment can hold a
// nearer point inside: a conductor in view costs a few clips, not one per segment.
class NearestPoints {
 public:
  struct Segment {
    double nearest2 = 0.0;  // the squared distance of the segment's nearest point
    Eigen::Vector3d a, b;
  };
  explicit NearestPoints(std::vector<Segment>& scratch) : segments_(scratch) { segments_.clear(); }

  // The segment's nearest point, and the segment kept for clip().
  void add_segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    segments_.push_back({add_overall(a, b), a, b});
  }
  // The segment's nearest point alone; returns its squared distance.
  double add_overall(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const double t = nearest_on_segment(a, b);
    const Eigen::Vector3d point = a + t * (b - a);
    const double distance2 = point.squaredNorm();
    if (distance2 < overall2) {
      overall2 = distance2;
      overall_src = point;
    }
    return distance2;
  }
  // The segment's nearest point in the field, if nearer than the one so far.
  void clip_one(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const FieldOfView& field) {
    if (std::optional<double> in = field.nearest_inside(a, b)) {
      const Eigen::Vector3d seen = a + *in * (b - a);
      if (seen.squaredNorm() < inside2) {
        inside2 = seen.squaredNorm();
        inside_src = seen;
      }
    }
  }
  // True when the nearest point overall lies in the field: then it is the nearest inside too, and
  // no segment needs clipping (most objects in view: the field spans 42° by 36°).
  bool overall_inside(const FieldOfView& field) {
    if (!(overall2 < kInfinity) || !field.contains(overall_src)) return false;
    inside2 = overall2;
    inside_src = overall_src;
    return true;
  }
  // Every kept segment against the field, nearest first.
  void clip(const FieldOfView& field) {
    std::sort(segments_.begin(), segments_.end(),
              [](const Segment& x, const Segment& y) { return x.nearest2 < y.nearest2; });
    for (const Segment& segment : segments_) {
      if (segment.nearest2 >= inside2) break;
      clip_one(segment.a, segment.b, field);
    }
  }

  double overall2 = kInfinity;
  Eigen::Vector3d overall_src = Eigen::Vector3d::Zero();
  double inside2 = kInfinity;
  Eigen::Vector3d inside_src = Eigen::Vector3d::Zero();

 private:
  std::vector<Segment>& segments_;
};

// The float nearest `value` that is not below it.
float rounded_up(double value) {
  float f = static_cast<float>(value);
  if (static_cast<double>(f) < value) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

void FrameTruthModel::add_chunks(const Conductor& conductor, std::vector<ConductorChunk>& out) {
  const std::vector<Eigen::Vector3d>& points = conductor.points_enu_m;
  const auto vertices = static_cast<std::uint32_t>(points.size());
  if (vertices == 0) return;
  for (std::uint32_t first = 0;; first += kChunkSegments) {
    ConductorChunk chunk;
    chunk.first = first;
    chunk.last = std::min(first + kChunkSegments, vertices - 1);
    Eigen::AlignedBox3d box;
    for (std::uint32_t k = chunk.first; k <= chunk.last; ++k) box.extend(points[k]);
    chunk.centre = box.center();
    chunk.radius_m = rounded_up(0.5 * box.diagonal().norm());
    chunk.chord_a = (points[chunk.first] - chunk.centre).cast<float>();
    chunk.chord_b = (points[chunk.last] - chunk.centre).cast<float>();
    // The distance from the chord is convex along each segment: the vertices bound it.
    const Eigen::Vector3d a = chunk.centre + chunk.chord_a.cast<double>();
    const Eigen::Vector3d b = chunk.centre + chunk.chord_b.cast<double>();
    double deviation = 0.0;
    for (std::uint32_t k = chunk.first; k <= chunk.last; ++k) {
      const Eigen::Vector3d& p = points[k];
      const double t = nearest_on_segment(a - p, b - p);
      deviation = std::max(deviation, (a - p + t * (b - a)).norm());
    }
    chunk.deviation_m = rounded_up(deviation);
    out.push_back(chunk);
    if (chunk.last + 1 >= vertices) break;
  }
}

ObjectGrid::Sphere FrameTruthModel::sphere_of(std::uint32_t object) const {
  const std::size_t conductors = conductors_.size();
  if (object < conductors || object - conductors >= cylinders_.size()) return grid_.sphere(object);
  const CylinderShape& c = cylinders_[object - conductors];
  return {Eigen::Vector3d(c.east_m, c.north_m, c.centre_up_m), c.bound_m};
}

ScanField frame_field(const ScanParams& scan, const FrameSweep& sweep) {
  ScanField field;
  field.alpha_min_deg = kInfinity;
  field.alpha_max_deg = -kInfinity;
  for (int fiber = 1; fiber < scan.fibers_per_line; ++fiber) {
    const double alpha = fiber_alpha_deg(scan, fiber);
    field.alpha_min_deg = std::min(field.alpha_min_deg, alpha);
    field.alpha_max_deg = std::max(field.alpha_max_deg, alpha);
  }
  field.range_max_m = timeout_range_m(scan.counter);
  return frame_field(scan, sweep, field);
}

ScanField frame_field(const ScanParams& scan, const FrameSweep& sweep, const ScanField& fibers) {
  ScanField field = fibers;
  const double first = mirror_beta_deg(scan, sweep, 0);
  const double last = mirror_beta_deg(scan, sweep, scan.pulses_per_frame() - 1);
  const double sawtooth = std::abs(scan.sawtooth_deg);
  field.beta_min_deg = std::min(first, last) - sawtooth;
  field.beta_max_deg = std::max(first, last) + sawtooth;
  return field;
}

FrameTruthModel::FrameTruthModel(const Scene& scene, const ScanParams& scan, const Mount& mount,
                                 const PoseSource& poses)
    : scene_(&scene),
      scan_(scan),
      mount_(mount),
      poses_(&poses),
      range_max_m_(timeout_range_m(scan.counter)),
      fibers_(frame_field(scan, FrameSweep{})),
      grid_(scene) {
  conductors_.reserve(scene.conductors.size());
  for (const Conductor& conductor : scene.conductors) {
    const auto begin = static_cast<std::uint32_t>(chunks_.size());
    add_chunks(conductor, chunks_);
    conductors_.push_back({conductor.points_enu_m.data(), begin,
                           static_cast<std::uint32_t>(chunks_.size())});
  }
  cylinders_.reserve(scene.cylinders.size());
  for (std::size_t c = 0; c < scene.cylinders.size(); ++c) {
    const Cylinder& cylinder = scene.cylinders[c];
    const ObjectGrid::Sphere& sphere =
        grid_.sphere(static_cast<std::uint32_t>(scene.conductors.size() + c));
    cylinders_.push_back({cylinder.base_enu_m.x(), cylinder.base_enu_m.y(),
                          cylinder.base_enu_m.z(), cylinder.base_enu_m.z() + cylinder.height_m,
                          cylinder.radius_m, sphere.centre.z(), sphere.radius_m});
  }
}

FrameTruthModel::ObjectView FrameTruthModel::view_of(std::uint32_t object,
                                                     const SensorPlacement& placement,
                                                     const FieldOfView& field) const {
  const Scene& scene = *scene_;
  const Eigen::Matrix3d src_from_enu = placement.enu_from_src.transpose();
  const auto to_src = [&](const Eigen::Vector3d& enu) {
    return Eigen::Vector3d(src_from_enu * (enu - placement.origin_enu_m));
  };
  thread_local std::vector<NearestPoints::Segment> scratch;
  NearestPoints nearest(scratch);
  std::size_t index = object;
  if (index < scene.conductors.size()) {
    // Chunks of the polyline nearest first, each only while it can still hold a nearer point.
    const Eigen::Vector3d* points = conductors_[index].points;
    const ConductorChunk* chunks = chunks_.data() + conductors_[index].begin;
    thread_local std::vector<std::pair<double, std::uint32_t>> order;
    order.clear();
    for (std::uint32_t c = 0; c < conductors_[index].end - conductors_[index].begin; ++c) {
      // No point of the chunk is nearer than its chord less its deviation.
      const Eigen::Vector3d centre = chunks[c].centre - placement.origin_enu_m;
      const Eigen::Vector3d a = centre + chunks[c].chord_a.cast<double>();
      const Eigen::Vector3d b = centre + chunks[c].chord_b.cast<double>();
      const double gap = (a + nearest_on_segment(a, b) * (b - a)).norm() - chunks[c].deviation_m;
      order.emplace_back(std::max(0.0, gap), c);
    }
    std::sort(order.begin(), order.end());
    // A chunk's segments, their ends mapped by `at` (a one-vertex chunk is one point).
    const auto for_segments = [&](const ConductorChunk& chunk, const auto& at, const auto& visit) {
      Eigen::Vector3d previous = at(points[chunk.first]);
      if (chunk.first == chunk.last) visit(previous, previous);
      for (std::uint32_t k = chunk.first + 1; k <= chunk.last; ++k) {
        const Eigen::Vector3d next = at(points[k]);
        visit(previous, next);
        previous = next;
      }
    };
    const auto from_sensor = [&](const Eigen::Vector3d& enu) {
      return Eigen::Vector3d(enu - placement.origin_enu_m);
    };
    // The nearest point overall in offsets from the sensor (distances do not need the turn to
    // sensor axes): only the nearest one is turned.
    double overall2 = kInfinity;
    Eigen::Vector3d overall = Eigen::Vector3d::Zero();
    for (const auto& [gap, c] : order) {
      if (gap * gap >= overall2) break;
      for_segments(chunks[c], from_sensor, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
        const Eigen::Vector3d point = a + nearest_on_segment(a, b) * (b - a);
        if (point.squaredNorm() < overall2) {
          overall2 = point.squaredNorm();
          overall = point;
        }
      });
    }
    nearest.overall2 = overall2;
    nearest.overall_src = src_from_enu * overall;
    if (!nearest.overall_inside(field) &&
        field.may_hold_sphere(to_src(grid_.sphere(object).centre), grid_.sphere(object).radius_m)) {
      for (const auto& [gap, c] : order) {
        if (gap * gap >= nearest.inside2) break;
        if (!field.may_hold_sphere(to_src(chunks[c].centre), chunks[c].radius_m)) continue;
        for_segments(chunks[c], to_src, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
          // A segment whose nearest point is no nearer than the best inside cannot improve it.
          const Eigen::Vector3d closest = a + nearest_on_segment(a, b) * (b - a);
          if (closest.squaredNorm() < nearest.inside2) nearest.clip_one(a, b, field);
        });
      }
    }
  } else if ((index -= scene.conductors.size()) < scene.cylinders.size()) {
    // The nearest point of the solid cylinder in closed form; in the field, the vertical lines of
    // the surface the sensor sees: the nearest and the two silhouettes.
    const CylinderShape& cylinder = cylinders_[index];
    const Eigen::Vector2d axis(cylinder.east_m, cylinder.north_m);
    const Eigen::Vector2d toward = placement.origin_enu_m.head<2>() - axis;
    const double distance = toward.norm();
    const double bottom = cylinder.bottom_m;
    const double top = cylinder.top_m;
    const Eigen::Vector2d unit =
        distance > 0.0 ? Eigen::Vector2d(toward / distance) : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d facing = distance <= cylinder.radius_m
                                       ? Eigen::Vector2d(placement.origin_enu_m.head<2>())
                                       : Eigen::Vector2d(axis + cylinder.radius_m * unit);
    const Eigen::Vector3d closest(facing.x(), facing.y(),
                                  std::clamp(placement.origin_enu_m.z(), bottom, top));
    nearest.overall_src = to_src(closest);
    nearest.overall2 = nearest.overall_src.squaredNorm();
    if (!nearest.overall_inside(field) &&
        field.may_hold_sphere(to_src({axis.x(), axis.y(), cylinder.centre_up_m}),
                              cylinder.bound_m)) {
      const auto line_at = [&](const Eigen::Vector2d& xy) {
        nearest.clip_one(to_src({xy.x(), xy.y(), bottom}), to_src({xy.x(), xy.y(), top}), field);
      };
      line_at(facing);
      // Every point of a silhouette line lies at least the tangent length √(D² − r²) away: when
      // the facing line already has a point in the field that near, they cannot hold a nearer one.
      const double tangent2 = distance * distance - cylinder.radius_m * cylinder.radius_m;
      if (distance > cylinder.radius_m && nearest.inside2 > tangent2) {
        const Eigen::Vector2d across(-unit.y(), unit.x());
        const double cos_edge = cylinder.radius_m / distance;
        const double sin_edge = std::sqrt(std::max(0.0, 1.0 - cos_edge * cos_edge));
        line_at(axis + cylinder.radius_m * (cos_edge * unit + sin_edge * across));
        line_at(axis + cylinder.radius_m * (cos_edge * unit - sin_edge * across));
      }
    }
  } else {
    const TriangleMesh& mesh = scene.meshes[index - scene.cylinders.size()].mesh;
    for (const auto& triangle : mesh.triangles) {
      const Eigen::Vector3d corners[3] = {to_src(mesh.vertices[triangle[0]]),
                                          to_src(mesh.vertices[triangle[1]]),
                                          to_src(mesh.vertices[triangle[2]])};
      for (int edge = 0; edge < 3; ++edge) {
        nearest.add_segment(corners[edge], corners[(edge + 1) % 3]);
      }
    }
  }
  // Meshes whose bounding sphere lies wholly outside the field skip the clipping.
  if (object >= scene.conductors.size() + scene.cylinders.size() &&
      !nearest.overall_inside(field) &&
      field.may_hold_sphere(to_src(grid_.sphere(object).centre), grid_.sphere(object).radius_m)) {
    nearest.clip(field);
  }
  ObjectView view;
  view.in_view = nearest.inside2 < kInfinity;
  view.point_src = view.in_view ? nearest.inside_src : nearest.overall_src;
  view.range_m = view.point_src.norm();
  view.angles = field_angles(view.point_src);
  return view;
}

void FrameTruthModel::frame_truth(std::int64_t frame, const FrameSweep& sweep,
                                  std::span<const FrameTally::ObjectHit> hits,
                                  FrameTruth& out) const {
  out.frame = frame;
  out.time_s = pulse_time_s(scan_, frame, scan_.pulses_per_frame() / 2);
  out.rows.clear();
  const SensorPlacement placement =
      sensor_placement(poses_->pose_at(out.time_s), mount_, scan_.model);
  const Eigen::Vector3d velocity =
      (sensor_placement(poses_->pose_at(out.time_s + kVelocityStepS), mount_, scan_.model)
           .origin_enu_m -
       sensor_placement(poses_->pose_at(out.time_s - kVelocityStepS), mount_, scan_.model)
           .origin_enu_m) /
      (2.0 * kVelocityStepS);
  const FieldOfView field(frame_field(scan_, sweep, fibers_));
  const Eigen::Vector3d velocity_src = placement.enu_from_src.transpose() * velocity;

  // The objects near the sensor and those hit; returns counted per object in a per-thread table
  // (zeroed again below, so it costs the hits, not the scene); the objects marked in a bit set
  // and taken in index order from it.
  thread_local std::vector<std::uint32_t> near;
  thread_local std::vector<std::uint32_t> returns_of;
  thread_local std::vector<std::uint64_t> marked;
  near.clear();
  if (returns_of.size() < grid_.size()) returns_of.assign(grid_.size(), 0);
  if (marked.size() < (grid_.size() + 63) / 64) marked.assign((grid_.size() + 63) / 64, 0);
  const auto mark = [&](std::uint32_t object) {
    marked[object / 64] |= std::uint64_t{1} << (object % 64);
  };
  grid_.objects_in_cells_near(placement.origin_enu_m.x(), placement.origin_enu_m.y(), range_max_m_,
                              near);
  for (const std::uint32_t object : near) mark(object);
  for (const FrameTally::ObjectHit& hit : hits) {
    if (hit.object < grid_.size()) {
      ++returns_of[hit.object];
      mark(hit.object);
    }
  }

  for (std::size_t word = 0; word < marked.size(); ++word) {
    for (std::uint64_t bits = std::exchange(marked[word], 0); bits != 0; bits &= bits - 1) {
      const auto object = static_cast<std::uint32_t>(word * 64 + std::countr_zero(bits));
      const std::uint64_t returns = returns_of[object];
      returns_of[object] = 0;
      const ObjectGrid::Sphere b = sphere_of(object);
      if (returns == 0 && (b.centre - placement.origin_enu_m).squaredNorm() >
                              (range_max_m_ + b.radius_m) * (range_max_m_ + b.radius_m)) {
        continue;
      }
      const ObjectView view = view_of(object, placement, field);
      if (returns == 0 && view.range_m > range_max_m_) continue;
      TruthRow& row = out.rows.emplace_back();
      row.object = object;
      row.range_m = view.range_m;
      row.alpha_deg = view.angles.alpha_deg;
      row.beta_deg = view.angles.beta_deg;
      row.in_view = view.in_view;
      row.returns = returns;
      row.closing_speed_mps =
          view.range_m > 0.0 ? velocity_src.dot(view.point_src) / view.range_m : 0.0;
    }
  }
}

}  // namespace owsim
