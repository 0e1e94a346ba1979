#pragma once
// Which scene objects a frame could see (INTERFACE.md "Ground truth and detection evidence",
// docs/evidence.md "In view"): the denominator of every detection statistic, computed from the
// geometry alone — the trajectory's pose at the frame's middle, the frame's scanned field and the
// counter's timeout range — never from what was hit.
//
// For each named object (conductor, pole, tree, mesh) whose nearest point lies within the timeout
// range of the sensor at the frame's middle, or that has returns in the frame: the range and
// sensor-frame α, β of its nearest point inside the field (in_view) or, when no part is inside,
// of its nearest point overall; its returns; and the closing speed of the sensor on that point.
// Shapes as tested against the field (evaluation/field_of_view.hpp, exact per segment): a
// conductor by its polyline (the wire's radius, ≤ 2 cm, ignored), a pole or tree by the three
// vertical lines of its surface the sensor sees (the nearest and the two silhouette edges), a mesh
// by its triangles' edges. Objects are found through a uniform east/north grid, so a frame costs
// the objects within range, not the scene.
// The field is taken at one pose for the whole frame (1/3 s): an object at the field's edge may
// drift across it during the frame; docs/evidence.md bounds the effect.
#include <cstdint>
#include <span>
#include <vector>

#include "evaluation/field_of_view.hpp"
#include "evaluation/object_grid.hpp"
#include "geometry/scene.hpp"
#include "io/run/frame_truth.hpp"
#include "sensor/mounting.hpp"
#include "sensor/pose_source.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

// The field frame `sweep` scans: α from the lowest to the highest ranging fiber, β from the
// sweep's first to its last mirror angle widened by the sawtooth, out to the timeout range.
[[nodiscard]] ScanField frame_field(const ScanParams& scan, const FrameSweep& sweep);
// The same with α and the range of `fibers` (a frame_field of the same scan): β alone changes
// from frame to frame.
[[nodiscard]] ScanField frame_field(const ScanParams& scan, const FrameSweep& sweep,
                                    const ScanField& fibers);

class FrameTruthModel final : public FrameTruthSource {
 public:
  // `scene` and `poses` must outlive the model. Builds the object grid once.
  FrameTruthModel(const Scene& scene, const ScanParams& scan, const Mount& mount,
                  const PoseSource& poses);

  void frame_truth(std::int64_t frame, const FrameSweep& sweep,
                   std::span<const FrameTally::ObjectHit> hits, FrameTruth& out) const override;

  // One object seen from `placement` against `field` (what frame_truth computes per row, without
  // returns and closing speed): for tests.
  struct ObjectView {
    double range_m = 0.0;
    FieldAngles angles;
    bool in_view = false;
    Eigen::Vector3d point_src = Eigen::Vector3d::Zero();  // that point, in sensor axes
  };
  [[nodiscard]] ObjectView view_of(std::uint32_t object, const SensorPlacement& placement,
                                   const FieldOfView& field) const;

 private:
  // What a frame reads of the objects is packed here, in object order, apart from the scene's
  // records (ids, reflectivities, whole polylines): a frame visits the objects within range in
  // index order, and in a flight the cache holds the tracer's data, not these, so the bytes a
  // frame touches are much of what its ground truth costs (bench_frame_truth on the corridor
  // frame, cache emptied between frames: 175 us reading the scene's records, 145 us these; 65 us
  // with a warm cache).
  //
  // A run of a conductor's polyline, vertices first..last, in a bounding sphere and within
  // `deviation_m` of its chord (ends at centre + chord_a, centre + chord_b: a chunk of a catenary
  // is nearly straight, so the chord less the deviation bounds its distance far more tightly
  // than the sphere): the conductor's points are visited chunk by chunk, nearest first, only
  // while a chunk can hold a nearer point. One cache line; the chord's ends are floats (µm at a
  // chunk's size) and the deviation is taken from those ends, rounded up, so it stays a bound.
  struct ConductorChunk {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    float radius_m = 0.0F;
    float deviation_m = 0.0F;
    Eigen::Vector3f chord_a = Eigen::Vector3f::Zero();
    Eigen::Vector3f chord_b = Eigen::Vector3f::Zero();
    std::uint32_t first = 0, last = 0;
  };
  struct ConductorChunks {
    const Eigen::Vector3d* points = nullptr;  // the conductor's vertices
    std::uint32_t begin = 0, end = 0;         // its chunks in chunks_
  };
  // A pole or tree: its axis, bottom, top and radius, and the object grid's bounding sphere.
  struct CylinderShape {
    double east_m = 0.0, north_m = 0.0, bottom_m = 0.0, top_m = 0.0, radius_m = 0.0;
    double centre_up_m = 0.0, bound_m = 0.0;  // the sphere: (east, north, centre_up), bound_m
  };
  static constexpr std::uint32_t kChunkSegments = 16;
  static void add_chunks(const Conductor& conductor, std::vector<ConductorChunk>& out);
  // The bounding sphere of an object, as the object grid has it.
  [[nodiscard]] ObjectGrid::Sphere sphere_of(std::uint32_t object) const;

  const Scene* scene_;
  ScanParams scan_;
  Mount mount_;
  const PoseSource* poses_;
  double range_max_m_ = 0.0;
  ScanField fibers_;  // α and range of the scan, the same every frame
  ObjectGrid grid_;
  std::vector<ConductorChunk> chunks_;         // every conductor's, in conductor order
  std::vector<ConductorChunks> conductors_;    // by conductor
  std::vector<CylinderShape> cylinders_;       // by cylinder
};

}  // namespace owsim
