#pragma once
// The scene as Embree sees it (DESIGN.md "Engine decisions"), built once per scenario as two
// Embree scenes, traced one after the other for each pulse (engine/frame_tracer.hpp):
//   solids  — what stops the central ray:
//     meshes     — one triangle geometry per mesh object (buildings, lattice towers);
//     cylinders  — one USER geometry (poles and trees), intersected in double precision;
//     terrain    — over the region the sensor can reach: one triangle mesh, or for a DEM of more
//                  than kDemGridFromPosts posts grid primitives on its posts
//                  (engine/terrain_grids.hpp);
//     a triangle or grid hit is re-intersected in double (engine/frame_tracer.cpp).
//   A flat terrain is not in the BVH: its two triangles over the region (most pulses end on
//   them) are intersected in double for every ray before Embree's query, by the same test that
//   re-intersected Embree's float hit on them (level_ground), and the solids pass then
//   searches only up to that range. Two huge triangles in the BVH cost every ray a leaf test near
//   the root and a traversal of what lies behind the ground.
//   wires   — every conductor's segments in one FLAT_LINEAR_CURVE geometry (one Embree object
//             and vertex buffer however many conductors: 35,000 geometries cost a 5,000-span
//             grid 20 MB), its radius the *capture radius* r_wire + r_beam(max range) of the
//             segment's conductor (plus a float-safety margin). Embree tests a flat linear
//             segment in the plane across the ray: a hit is exactly "the ray passes within the
//             radius of the segment" (its end points included), reported once, at the depth of
//             the segment's nearest point. So every pulse whose beam can touch the wire reaches
//             the intersection filter, which applies the exact double-precision rule of
//             sensor/pulse_candidates.hpp to segments in front of the pulse's solid hit and
//             rejects the hit so traversal continues. (Round curves, tried first, are 3-D
//             capsules with the same reach, a far dearer test, and report entry and exit.)
// The solids are built in robust mode (watertight triangles, conservative bounds); the wires, whose
// capture radius holds a float-safety margin, are not (embree_scene.cpp new_scene).
// Float coordinates are offsets from the scenario origin, converted from double once here.
// The scene is immutable after construction and may be traced from any number of threads.
#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "engine/embree_device.hpp"
#include "engine/terrain_grids.hpp"
#include "geometry/scene.hpp"
#include "sensor/pulse_candidates.hpp"
#include "sensor/receiver.hpp"

namespace owsim {

// The wires geometry's segments by conductor: its segment k is segment k − first_segment[c] of
// conductor c = conductor_of[k] (also the conductor's object index). The conductor filter's
// geometry user data.
struct WireSegments {
  std::vector<std::uint32_t> conductor_of;   // by segment of the geometry
  std::vector<std::uint32_t> first_segment;  // by conductor
};

// A DEM of up to this many posts in reach is traced as triangles, ~10 % faster than Embree's grid
// primitives but ~250 bytes a post instead of ~15 (README "Terrain from a DEM"): up to 250 MB.
inline constexpr std::size_t kDemGridFromPosts = 1'000'000;

class EmbreeScene {
 public:
  // `region` bounds the terrain mesh (east, north); `max_range_m` sizes the wire capture radius.
  // A DEM of more than `dem_grid_from_posts` posts becomes grid primitives, a smaller one
  // triangles (see kDemGridFromPosts).
  EmbreeScene(const EmbreeDevice& device, const Scene& scene, const ReceiverParams& receiver,
              const Eigen::AlignedBox2d& region, double max_range_m,
              std::size_t dem_grid_from_posts = kDemGridFromPosts);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Meshes, cylinders and a terrain that is not flat.
  [[nodiscard]] RTCScene solids() const { return solids_; }
  [[nodiscard]] RTCScene wires() const { return wires_; }  // conductors
  [[nodiscard]] const Scene& scene() const { return *objects_; }
  [[nodiscard]] const ReceiverParams& receiver() const { return receiver_; }
  // The terrain's triangles over the region, built on each call (the brute-force tracer's and
  // tests' view of the surface the Embree scene traces).
  [[nodiscard]] TriangleMesh terrain_mesh() const { return scene().terrain.mesh(region_); }
  // The pulse's exact range and normal on the terrain where Embree reported `hit` (on one of
  // the terrain's geometries).
  [[nodiscard]] TriangleHit terrain_hit(const RTCHit& hit, const PulseRay& ray) const;
  // The pulse's exact range and normal on triangle `prim_id` of mesh `mesh` (its geomID).
  [[nodiscard]] TriangleHit mesh_hit(unsigned mesh, unsigned prim_id, const PulseRay& ray) const;
  [[nodiscard]] const WireSegments& wire_segments() const { return wire_segments_; }
  // r_wire + r_beam(max range), widened by the float-safety margin.
  [[nodiscard]] double capture_radius_m(const Conductor& conductor) const;
  // Bounds of every conductor's flat curve, widened by a float-safety margin: a pulse's ray
  // that misses them in double cannot meet a wire in Embree's float test (empty: no conductors).
  [[nodiscard]] const Eigen::AlignedBox3d& wire_bounds() const { return wire_bounds_; }
  // Embree's tfar for a search up to a hit at `range_m` (the wire pass in front of the solid, the
  // solids pass in front of the level ground): a little beyond it, so float rounding of a depth
  // Embree reports cannot hide what lies in front of that hit.
  [[nodiscard]] static float search_end(double range_m);
  // A flat terrain's two triangles over the region, traced outside Embree: a ray's ground is the
  // first of them intersect_triangle accepts (geometry/ray_triangle.hpp first_triangle_hits), from
  // 0 on. Empty when the terrain is not flat.
  [[nodiscard]] const std::vector<TriangleFrame>& level_ground() const { return level_ground_; }
  [[nodiscard]] bool has_level_ground() const { return !level_ground_.empty(); }

  // Geometry ids: wires() holds geometry 0 (when there are conductors); in solids(), mesh m is
  // geomID m, then
  // come the cylinders and the terrain's one or two geometries (RTC_INVALID_GEOMETRY_ID when
  // absent, and for a flat terrain, which is not in the BVH).
  [[nodiscard]] unsigned cylinders_geom_id() const { return cylinders_geom_; }
  [[nodiscard]] unsigned terrain_geom_id() const { return terrain_geom_; }
  // A DEM's tiles with holes, as triangles (engine/terrain_grids.hpp).
  [[nodiscard]] unsigned terrain_patches_geom_id() const { return terrain_patches_geom_; }
  [[nodiscard]] bool has_terrain() const {
    return has_level_ground() || terrain_geom_ != RTC_INVALID_GEOMETRY_ID ||
           terrain_patches_geom_ != RTC_INVALID_GEOMETRY_ID;
  }
  [[nodiscard]] bool is_terrain(unsigned geom_id) const {
    return geom_id != RTC_INVALID_GEOMETRY_ID &&
           (geom_id == terrain_geom_ || geom_id == terrain_patches_geom_);
  }

 private:
  void attach_conductors(const EmbreeDevice& device);
  void attach_cylinders(const EmbreeDevice& device);
  unsigned attach_triangles(const EmbreeDevice& device, const TriangleMesh& mesh, const char* what);
  void attach_terrain(const EmbreeDevice& device, std::size_t dem_grid_from_posts);

  const Scene* objects_;
  ReceiverParams receiver_;
  double max_range_m_;
  Eigen::AlignedBox2d region_;
  Eigen::AlignedBox3d wire_bounds_;
  TriangleMesh terrain_triangles_;  // a flat or grid terrain
  // Each triangle's edges and normal, computed once (geometry/ray_triangle.hpp): of the grid
  // terrain, of the flat terrain (level_ground_), of a DEM's patches, and of each mesh by geomID.
  std::vector<TriangleFrame> terrain_frames_;
  std::vector<TriangleFrame> level_ground_;
  std::vector<TriangleFrame> patch_frames_;
  std::vector<std::vector<TriangleFrame>> mesh_frames_;
  std::optional<TerrainGrids> terrain_grids_;  // a DEM
  WireSegments wire_segments_;
  RTCScene solids_ = nullptr;
  RTCScene wires_ = nullptr;
  unsigned cylinders_geom_ = RTC_INVALID_GEOMETRY_ID;
  unsigned terrain_geom_ = RTC_INVALID_GEOMETRY_ID;
  unsigned terrain_patches_geom_ = RTC_INVALID_GEOMETRY_ID;
};

}  // namespace owsim
