#include "engine/embree_scene.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/trace_context.hpp"
#include "geometry/error.hpp"
#include "geometry/ray_triangle.hpp"
#include "sensor/beam.hpp"

namespace owsim {
namespace {

// Float rounding of the curve and of the ray may move a grazing beam by a few µm; the capture
// radius is widened by this much so the exact filter, not float rounding, decides.
constexpr double kCaptureMarginRelative = 1e-3;
constexpr double kCaptureMarginAbsolute_m = 1e-3;
// Embree reports a flat segment's hit at the depth of its point nearest the ray, and a triangle's
// or a cylinder's at its float depth, computed from offsets of at most a few km (errors well under
// a millimetre); a search up to a hit reaches this far beyond it, so the exact range comparison
// decides (the wire filter's against the solid, the tracer's of a solid against the level ground).
constexpr double kDepthMarginRelative = 1e-5;
constexpr double kDepthMarginAbsolute_m = 1e-3;
// The wires' bounds reach this far beyond every capture radius (plus 1e-5 of the largest
// coordinate and range): float rounding moves a ray by micrometres per metre of its offsets, so a
// ray that misses these bounds in double misses every flat curve in float.
constexpr double kBoundsMargin_m = 1.0;
constexpr double kBoundsMarginRelative = 1e-5;

// Intersection filter of a conductor: the exact §7 wire test in double precision; the hit is
// recorded as a candidate and always rejected so traversal goes on to what lies behind. The wire
// pass runs after the solid pass, so a segment whose closest approach lies at or beyond the
// pulse's solid hit is never offered: the conductor's candidate is its strongest visible segment,
// whatever order Embree visits the segments in.
void conductor_filter(const RTCFilterFunctionNArguments* args) {
  const auto* wires = static_cast<const WireSegments*>(args->geometryUserPtr);
  const TraceContext* context = trace_context(args->context);
  if (context->traversal_only) {
    for (unsigned i = 0; i < args->N; ++i) args->valid[i] = 0;
    return;
  }
  const ReceiverParams& receiver = context->scene->receiver();
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    args->valid[i] = 0;
    const unsigned id = RTCRayN_id(args->ray, args->N, i);
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const std::uint32_t conductor = wires->conductor_of[prim];
    const std::size_t segment = prim - wires->first_segment[conductor];
    PulseCandidates& pulse = context->candidates[id];
    Candidate candidate;
    if (wire_segment_candidate(context->rays[id], context->scene->scene().conductors[conductor],
                               segment, conductor, receiver, candidate) &&
        candidate.range_m <= context->max_range_m &&
        (!pulse.has_solid() || candidate.range_m < pulse.solid().range_m)) {
      pulse.offer_wire(candidate);
    }
  }
}

void cylinders_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* cylinders = static_cast<const std::vector<Cylinder>*>(args->geometryUserPtr);
  const Eigen::AlignedBox3d box = bounds((*cylinders)[args->primID]);
  // Round outwards so the float box contains the double cylinder.
  args->bounds_o->lower_x = std::nextafter(static_cast<float>(box.min().x()), -INFINITY);
  args->bounds_o->lower_y = std::nextafter(static_cast<float>(box.min().y()), -INFINITY);
  args->bounds_o->lower_z = std::nextafter(static_cast<float>(box.min().z()), -INFINITY);
  args->bounds_o->upper_x = std::nextafter(static_cast<float>(box.max().x()), INFINITY);
  args->bounds_o->upper_y = std::nextafter(static_cast<float>(box.max().y()), INFINITY);
  args->bounds_o->upper_z = std::nextafter(static_cast<float>(box.max().z()), INFINITY);
}

// Ray–cylinder in double from the pulse's own ray (eq 6.7–6.10); the nearest accepted hit is
// kept per ray so the post-pass needs no float round trip.
void cylinders_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto* cylinders = static_cast<const std::vector<Cylinder>*>(args->geometryUserPtr);
  TraceContext* context = trace_context(args->context);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  const Cylinder& cylinder = (*cylinders)[args->primID];
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned id = RTCRayN_id(rays, args->N, i);
    const PulseRay& ray = context->rays[id];
    unsigned& record_prim = context->cylinder_prims[id - context->chunk_begin];
    CylinderHit& record_hit = context->cylinder_hits[id - context->chunk_begin];
    const float t_far = RTCRayN_tfar(rays, args->N, i);
    // While a cylinder is the nearest hit, compare with its exact range, not the float tfar: a
    // nearer cylinder within one float step, or a coincident one (consecutive spans share a
    // support), is then decided in double, and equal ranges go to the lower cylinder index as in
    // the brute-force tracer, whatever order Embree visits them in.
    const bool cylinder_nearest =
        record_prim != RTC_INVALID_GEOMETRY_ID && static_cast<float>(record_hit.t) == t_far;
    const double t_max = cylinder_nearest ? record_hit.t : static_cast<double>(t_far);
    const auto hit =
        intersect(cylinder, ray.origin_enu_m, ray.dir_enu, RTCRayN_tnear(rays, args->N, i), t_max);
    if (!hit) continue;
    if (cylinder_nearest && hit->t == record_hit.t && record_prim < args->primID) continue;
    RTCRayN_tfar(rays, args->N, i) = static_cast<float>(hit->t);
    RTCHitN_Ng_x(hits, args->N, i) = static_cast<float>(hit->normal.x());
    RTCHitN_Ng_y(hits, args->N, i) = static_cast<float>(hit->normal.y());
    RTCHitN_Ng_z(hits, args->N, i) = static_cast<float>(hit->normal.z());
    RTCHitN_u(hits, args->N, i) = 0.0f;
    RTCHitN_v(hits, args->N, i) = 0.0f;
    RTCHitN_primID(hits, args->N, i) = args->primID;
    RTCHitN_geomID(hits, args->N, i) = args->geomID;
    RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
    record_prim = args->primID;
    record_hit = *hit;
  }
}

// Robust mode (watertight triangle tests, conservative box tests) where a ray through a terrain
// edge or corner must not slip between two triangles the double-precision brute force sees as
// closed: the solids. The wires need no more than their capture radius's float-safety margin: a
// beam that can touch a conductor passes that margin (≥ 1 mm) inside the flat curve, the allowance
// already made for the float curve test itself, whose rounding is of a box test's order; robust
// mode's conservative boxes cost ~3 % of a one-thread corridor run (the same bytes either way on
// every example).
RTCScene new_scene(const EmbreeDevice& device, RTCSceneFlags flags) {
  RTCScene scene = rtcNewScene(device.get());
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene, flags);
  return scene;
}

}  // namespace

EmbreeScene::EmbreeScene(const EmbreeDevice& device, const Scene& scene,
                         const ReceiverParams& receiver, const Eigen::AlignedBox2d& region,
                         double max_range_m, std::size_t dem_grid_from_posts)
    : objects_(&scene), receiver_(receiver), max_range_m_(max_range_m), region_(region) {
  if (!(std::isfinite(max_range_m) && max_range_m > 0.0)) {
    throw Error("engine: the maximum range must be positive and finite");
  }
  for (const Conductor& conductor : scene.conductors) {
    if (conductor.points_enu_m.size() < 2) {
      throw Error("engine: conductor " + conductor.id + " has fewer than two points");
    }
  }
  solids_ = new_scene(device, RTC_SCENE_FLAG_ROBUST);
  wires_ = new_scene(device, RTC_SCENE_FLAG_NONE);
  if (!scene.conductors.empty()) attach_conductors(device);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (attach_triangles(device, scene.meshes[m].mesh, "adding a mesh") != m) {
      throw Error("engine: unexpected mesh geometry id");
    }
    mesh_frames_.push_back(triangle_frames(scene.meshes[m].mesh));
  }
  if (!scene.cylinders.empty()) attach_cylinders(device);
  attach_terrain(device, dem_grid_from_posts);
  rtcCommitScene(solids_);
  rtcCommitScene(wires_);
  device.check("building the scene");
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(wires_);
  rtcReleaseScene(solids_);
}

double EmbreeScene::capture_radius_m(const Conductor& conductor) const {
  const double radius = conductor.radius_m + beam_radius_m(max_range_m_, receiver_.beam);
  return radius * (1.0 + kCaptureMarginRelative) + kCaptureMarginAbsolute_m;
}

float EmbreeScene::search_end(double range_m) {
  const double end = range_m * (1.0 + kDepthMarginRelative) + kDepthMarginAbsolute_m;
  const auto rounded = static_cast<float>(end);
  // The next float up: one step of the bits for a finite non-negative float (what nextafter
  // gives, without its call on every pulse).
  if (rounded >= 0.0f && rounded < std::numeric_limits<float>::max()) {
    return std::bit_cast<float>(std::bit_cast<std::uint32_t>(rounded) + 1u);
  }
  return std::nextafter(rounded, INFINITY);
}

void EmbreeScene::attach_conductors(const EmbreeDevice& device) {
  const std::vector<Conductor>& conductors = scene().conductors;
  std::size_t points = 0;
  std::size_t segments = 0;
  for (const Conductor& conductor : conductors) {
    points += conductor.points_enu_m.size();
    segments += conductor.points_enu_m.size() - 1;
  }
  if (points > std::numeric_limits<unsigned>::max()) {
    throw Error("engine: more conductor points than Embree can index");
  }
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), points));
  auto* starts = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), segments));
  wire_segments_.conductor_of.resize(segments);
  wire_segments_.first_segment.resize(conductors.size());
  std::size_t vertex = 0;
  std::size_t segment = 0;
  for (std::size_t c = 0; c < conductors.size(); ++c) {
    const Conductor& conductor = conductors[c];
    const auto radius = static_cast<float>(capture_radius_m(conductor));
    wire_segments_.first_segment[c] = static_cast<std::uint32_t>(segment);
    for (std::size_t p = 0; p < conductor.points_enu_m.size(); ++p, ++vertex) {
      const Eigen::Vector3d& point = conductor.points_enu_m[p];
      const Eigen::Vector3d reach = Eigen::Vector3d::Constant(static_cast<double>(radius));
      wire_bounds_.extend(point - reach);
      wire_bounds_.extend(point + reach);
      vertices[4 * vertex + 0] = static_cast<float>(point.x());
      vertices[4 * vertex + 1] = static_cast<float>(point.y());
      vertices[4 * vertex + 2] = static_cast<float>(point.z());
      vertices[4 * vertex + 3] = radius;
      if (p + 1 == conductor.points_enu_m.size()) continue;
      starts[segment] = static_cast<unsigned>(vertex);
      wire_segments_.conductor_of[segment] = static_cast<std::uint32_t>(c);
      ++segment;
    }
  }
  const double largest =
      std::max(wire_bounds_.min().cwiseAbs().maxCoeff(), wire_bounds_.max().cwiseAbs().maxCoeff());
  const Eigen::Vector3d margin =
      Eigen::Vector3d::Constant(kBoundsMargin_m + kBoundsMarginRelative * (largest + max_range_m_));
  wire_bounds_ = Eigen::AlignedBox3d(wire_bounds_.min() - margin, wire_bounds_.max() + margin);
  rtcSetGeometryUserData(geometry, &wire_segments_);
  rtcSetGeometryIntersectFilterFunction(geometry, conductor_filter);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(wires_, geometry);
  rtcReleaseGeometry(geometry);
  device.check("adding the conductors");
}

void EmbreeScene::attach_cylinders(const EmbreeDevice& device) {
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(scene().cylinders.size()));
  rtcSetGeometryUserData(geometry, const_cast<std::vector<Cylinder>*>(&scene().cylinders));
  rtcSetGeometryBoundsFunction(geometry, cylinders_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, cylinders_intersect);
  rtcCommitGeometry(geometry);
  cylinders_geom_ = rtcAttachGeometry(solids_, geometry);
  rtcReleaseGeometry(geometry);
  device.check("adding poles and trees");
}

void EmbreeScene::attach_terrain(const EmbreeDevice& device, std::size_t dem_grid_from_posts) {
  const Terrain& terrain = scene().terrain;
  if (terrain.kind == TerrainKind::dem && terrain.dem->posts.size() > dem_grid_from_posts) {
    terrain_grids_.emplace(*terrain.dem, region_);
    if (terrain_grids_->grid_count() > 0) {
      RTCGeometry geometry = terrain_grids_->grid_geometry(device.get());
      terrain_geom_ = rtcAttachGeometry(solids_, geometry);
      rtcReleaseGeometry(geometry);
      device.check("adding the terrain");
    }
    if (!terrain_grids_->patches().triangles.empty()) {
      terrain_patches_geom_ =
          attach_triangles(device, terrain_grids_->patches(), "adding the terrain");
      patch_frames_ = triangle_frames(terrain_grids_->patches());
    }
    return;
  }
  if (terrain.kind == TerrainKind::flat) {
    level_ground_ = triangle_frames(terrain.mesh(region_));
    return;
  }
  terrain_triangles_ = terrain.mesh(region_);
  if (!terrain_triangles_.triangles.empty()) {
    terrain_geom_ = attach_triangles(device, terrain_triangles_, "adding the terrain");
    terrain_frames_ = triangle_frames(terrain_triangles_);
  }
}

TriangleHit EmbreeScene::terrain_hit(const RTCHit& hit, const PulseRay& ray) const {
  if (hit.geomID == terrain_patches_geom_) {
    return exact_mesh_hit(patch_frames_, hit.primID, ray.origin_enu_m, ray.dir_enu);
  }
  if (terrain_grids_) return terrain_grids_->exact_grid_hit(hit.primID, hit.u, hit.v, ray);
  return exact_mesh_hit(terrain_frames_, hit.primID, ray.origin_enu_m, ray.dir_enu);
}

TriangleHit EmbreeScene::mesh_hit(unsigned mesh, unsigned prim_id, const PulseRay& ray) const {
  return exact_mesh_hit(mesh_frames_[mesh], prim_id, ray.origin_enu_m, ray.dir_enu);
}

unsigned EmbreeScene::attach_triangles(const EmbreeDevice& device, const TriangleMesh& mesh,
                                       const char* what) {
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               mesh.vertices.size()));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int axis = 0; axis < 3; ++axis) {
      vertices[3 * v + static_cast<std::size_t>(axis)] = static_cast<float>(mesh.vertices[v][axis]);
    }
  }
  auto* triangles = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh.triangles.size()));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t corner = 0; corner < 3; ++corner) {
      triangles[3 * t + corner] = mesh.triangles[t][corner];
    }
  }
  rtcCommitGeometry(geometry);
  const unsigned geom_id = rtcAttachGeometry(solids_, geometry);
  rtcReleaseGeometry(geometry);
  device.check(what);
  return geom_id;
}

}  // namespace owsim
