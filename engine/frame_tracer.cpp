#include "engine/frame_tracer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include "engine/flush_to_zero.hpp"
#include "engine/trace_context.hpp"
#include "geometry/error.hpp"
#include "geometry/ray_box.hpp"
#include "geometry/ray_triangle.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

constexpr unsigned kNoHit = RTC_INVALID_GEOMETRY_ID;

void set_ray(RTCRay& ray, const PulseRay& pulse, unsigned id, float tfar) {
  ray.org_x = static_cast<float>(pulse.origin_enu_m.x());
  ray.org_y = static_cast<float>(pulse.origin_enu_m.y());
  ray.org_z = static_cast<float>(pulse.origin_enu_m.z());
  ray.dir_x = static_cast<float>(pulse.dir_enu.x());
  ray.dir_y = static_cast<float>(pulse.dir_enu.y());
  ray.dir_z = static_cast<float>(pulse.dir_enu.z());
  ray.tnear = 0.0f;
  ray.tfar = tfar;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;  // Debian's Embree is built with ray masks
  ray.id = id;
  ray.flags = 0;
}

// The sunlight a solid hit scatters into the receiver (SENSOR-SPEC §11): 0 without sunlight.
double solid_background(const ReceiverNoise& noise, const Eigen::Vector3d& normal,
                        const PulseRay& ray, double reflectivity) {
  return noise.sunlit() ? noise.solid_background(normal, ray.dir_enu, reflectivity) : 0.0;
}

// The pulse's solid candidate in double: the nearest solid Embree reported, or the level ground
// where it lies nearer (or Embree reported none); its angle and energy are left to the chunk's
// batch (the terms go there).
void record_solid(const EmbreeScene& scene, const ReceiverNoise& noise, const PulseRay& ray,
                  const RTCHit& solid, unsigned cylinder_prim, const CylinderHit& cylinder_hit,
                  const std::optional<TriangleHit>& ground, PulseCandidates& out,
                  SurfaceEnergyBatch& batch) {
  const Scene& objects = scene.scene();
  const ReceiverParams& receiver = scene.receiver();
  const auto set_solid = [&](double range_m, const SurfaceTerms& terms, std::uint32_t object,
                             SurfaceClass surface, const Eigen::Vector3d& normal) {
    out.set_solid(solid_candidate(range_m, {}, object, surface),
                  solid_background(noise, normal, ray, terms.reflectivity));
    batch.add(terms);
  };
  const auto set_ground = [&](const TriangleHit& hit) {
    set_solid(
        hit.t,
        extended_surface_terms(ray, hit.t, hit.normal, objects.terrain.reflectivity, receiver),
        ground_object_index(objects), SurfaceClass::ground, hit.normal);
  };
  const unsigned geom_id = solid.geomID, prim_id = solid.primID;
  if (geom_id == kNoHit) {
    if (ground) set_ground(*ground);
    return;
  }
  if (geom_id < objects.meshes.size()) {
    const MeshObject& mesh = objects.meshes[geom_id];
    const TriangleHit hit = scene.mesh_hit(geom_id, prim_id, ray);
    if (ground && ground->t < hit.t) {
      set_ground(*ground);
      return;
    }
    set_solid(hit.t, extended_surface_terms(ray, hit.t, hit.normal, mesh.reflectivity, receiver),
              mesh_object_index(objects, geom_id), mesh.surface, hit.normal);
    return;
  }
  if (geom_id == scene.cylinders_geom_id()) {
    if (cylinder_prim != prim_id) throw Error("engine: cylinder hit record out of step");
    if (ground && ground->t < cylinder_hit.t) {
      set_ground(*ground);
      return;
    }
    const Cylinder& cylinder = objects.cylinders[prim_id];
    set_solid(cylinder_hit.t, cylinder_terms(ray, cylinder, cylinder_hit, receiver),
              cylinder_object_index(objects, prim_id), cylinder.surface, cylinder_hit.normal);
    return;
  }
  if (scene.is_terrain(geom_id)) set_ground(scene.terrain_hit(solid, ray));
}

// An Embree ray packet of W rays (8 or 16) and its query.
template <unsigned W>
struct Packet {
  static_assert(W == 8 || W == 16);
  using RayHit = std::conditional_t<W == 8, RTCRayHit8, RTCRayHit16>;
  static void intersect(const int* valid, RTCScene scene, RTCIntersectContext* context,
                        RayHit* packet) {
    if constexpr (W == 8) {
      rtcIntersect8(valid, scene, context, packet);
    } else {
      rtcIntersect16(valid, scene, context, packet);
    }
  }
};

// The packets of a block's rays, W rays each.
template <unsigned W>
class BlockPackets {
 public:
  static_assert(FrameTracer::kChunk % W == 0);
  using RayHit = typename Packet<W>::RayHit;

  // Rays [0, n) in packets: ray i from the block's arrays (its pulse's doubles), with id ids[i],
  // from 0 to tfar[i], no hit. The lanes of the last packet past n repeat its first ray (Embree
  // skips them: they are not valid); the arrays, ids and tfar are padded so. Field by field over
  // whole packets, on vector lanes. Returns the padded count.
  unsigned set(RayArrays& arrays, std::array<unsigned, FrameTracer::kChunk>& ids,
               std::array<float, FrameTracer::kChunk>& tfar, unsigned n) {
    const unsigned padded = (n + W - 1) / W * W;
    for (unsigned i = n; i < padded; ++i) {
      const unsigned first = i - i % W;
      for (int axis = 0; axis < 3; ++axis) {
        arrays.origin[axis][i] = arrays.origin[axis][first];
        arrays.dir[axis][i] = arrays.dir[axis][first];
      }
      ids[i] = ids[first];
      tfar[i] = tfar[first];
    }
    for (unsigned p = 0; p < padded / W; ++p) {
      RayHit& packet = packets_[p];
      const unsigned at = p * W;
      for (unsigned lane = 0; lane < W; ++lane) {
        packet.ray.org_x[lane] = static_cast<float>(arrays.origin[0][at + lane]);
        packet.ray.org_y[lane] = static_cast<float>(arrays.origin[1][at + lane]);
        packet.ray.org_z[lane] = static_cast<float>(arrays.origin[2][at + lane]);
        packet.ray.dir_x[lane] = static_cast<float>(arrays.dir[0][at + lane]);
        packet.ray.dir_y[lane] = static_cast<float>(arrays.dir[1][at + lane]);
        packet.ray.dir_z[lane] = static_cast<float>(arrays.dir[2][at + lane]);
        packet.ray.tnear[lane] = 0.0f;
        packet.ray.tfar[lane] = tfar[at + lane];
        packet.ray.time[lane] = 0.0f;
        packet.ray.mask[lane] = 0xFFFFFFFFu;  // Debian's Embree is built with ray masks
        packet.ray.id[lane] = ids[at + lane];
        packet.ray.flags[lane] = 0;
        packet.hit.geomID[lane] = kNoHit;
        packet.hit.instID[0][lane] = kNoHit;
      }
    }
    return padded;
  }
  // Ray i from 0 to tfar again, its hit cleared.
  void restart(unsigned i, float tfar) {
    RayHit& packet = packets_[i / W];
    packet.ray.tfar[i % W] = tfar;
    packet.hit.geomID[i % W] = kNoHit;
    packet.hit.instID[0][i % W] = kNoHit;
  }
  // restart(i, t_max[i]) for the rays [0, n), over whole packets where they are full.
  void restart(const double* t_max, unsigned n) {
    for (unsigned at = 0; at < n; at += W) {
      RayHit& packet = packets_[at / W];
      if (at + W <= n) {
        for (unsigned lane = 0; lane < W; ++lane) {
          packet.ray.tfar[lane] = static_cast<float>(t_max[at + lane]);
          packet.hit.geomID[lane] = kNoHit;
          packet.hit.instID[0][lane] = kNoHit;
        }
        continue;
      }
      for (unsigned lane = 0; at + lane < n; ++lane)
        restart(at + lane, static_cast<float>(t_max[at + lane]));
    }
  }
  [[nodiscard]] float tfar(unsigned i) const { return packets_[i / W].ray.tfar[i % W]; }
  [[nodiscard]] RTCHit hit(unsigned i) const {
    const auto& packet = packets_[i / W].hit;
    RTCHit hit{};
    hit.geomID = packet.geomID[i % W];
    hit.primID = packet.primID[i % W];
    hit.u = packet.u[i % W];
    hit.v = packet.v[i % W];
    return hit;
  }
  // One query per packet that holds a traced ray of [0, n); the others are not handed to Embree.
  void intersect(RTCScene scene, TraceContext& context, const std::uint8_t* traced, unsigned n) {
    context.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (unsigned first = 0; first < n; first += W) {
      alignas(64) int valid[W];
      int any = 0;
      for (unsigned lane = 0; lane < W; ++lane) {
        valid[lane] = first + lane < n && traced[first + lane] != 0 ? -1 : 0;
        any |= valid[lane];
      }
      if (any != 0) Packet<W>::intersect(valid, scene, &context.rtc, &packets_[first / W]);
    }
  }

 private:
  std::array<RayHit, FrameTracer::kChunk / W> packets_;
};

// A block's rays in the form its Embree query takes them: RTCRayHit records (per ray, stream) or
// ray packets (packet8, packet16), each ray written once in float and, between the two passes,
// only given a new tfar and cleared of its hit (Embree changes nothing else of a ray).
class BlockRays {
 public:
  explicit BlockRays(TraceApi api) : api_(api) {}

  [[nodiscard]] bool in_packets() const {
    return api_ == TraceApi::packet8 || api_ == TraceApi::packet16;
  }
  // Ray i of the block (per ray and stream only): the pulse's ray as floats, from 0 to tfar, no
  // hit.
  void set(unsigned i, const PulseRay& pulse, unsigned id, float tfar) {
    traced_[i] = 1;
    set_ray(rayhits_[i].ray, pulse, id, tfar);
    clear_hit(rayhits_[i].hit);
  }
  // Rays [0, n) of the block in packets (packet8, packet16 only), as BlockPackets::set writes
  // them (the arrays, ids and tfar padded to whole packets).
  void set_packets(RayArrays& arrays, std::array<unsigned, FrameTracer::kChunk>& ids,
                   std::array<float, FrameTracer::kChunk>& tfar, unsigned n) {
    const unsigned padded = api_ == TraceApi::packet16 ? packets16_.set(arrays, ids, tfar, n)
                                                       : packets8_.set(arrays, ids, tfar, n);
    std::fill_n(traced_.begin(), padded, std::uint8_t{1});
  }
  // Ray i again from 0 to tfar, its hit cleared (per ray and stream only); `traced` false leaves
  // it out of the next query.
  void restart(unsigned i, float tfar, bool traced) {
    traced_[i] = traced ? 1 : 0;
    rayhits_[i].ray.tfar = tfar;
    // A stream leaves out a ray whose tnear lies beyond its tfar.
    rayhits_[i].ray.tnear = traced ? 0.0f : std::numeric_limits<float>::infinity();
    clear_hit(rayhits_[i].hit);
  }
  // restart(i, t_max[i], meets[i] != 0) for the rays [0, n) of packets (packet8, packet16 only),
  // over whole packets where they are full.
  void restart_packets(const double* t_max, const std::int64_t* meets, unsigned n) {
    for (unsigned i = 0; i < n; ++i) traced_[i] = meets[i] != 0 ? 1 : 0;
    if (api_ == TraceApi::packet16) {
      packets16_.restart(t_max, n);
    } else {
      packets8_.restart(t_max, n);
    }
  }
  [[nodiscard]] float tfar(unsigned i) const {
    if (api_ == TraceApi::packet16) return packets16_.tfar(i);
    if (api_ == TraceApi::packet8) return packets8_.tfar(i);
    return rayhits_[i].ray.tfar;
  }
  // What record_solid reads of ray i's hit: geometry, primitive, u, v.
  [[nodiscard]] RTCHit hit(unsigned i) const {
    if (api_ == TraceApi::packet16) return packets16_.hit(i);
    if (api_ == TraceApi::packet8) return packets8_.hit(i);
    return rayhits_[i].hit;
  }

  // One Embree query over the traced rays of [0, n), in the chosen form; a packet without one
  // is not handed to Embree at all.
  void intersect(RTCScene scene, TraceContext& context, unsigned n) {
    switch (api_) {
      case TraceApi::per_ray:
        for (unsigned i = 0; i < n; ++i) {
          if (traced_[i] != 0) rtcIntersect1(scene, &context.rtc, &rayhits_[i]);
        }
        break;
      case TraceApi::stream:
        context.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect1M(scene, &context.rtc, rayhits_.data(), n, sizeof(RTCRayHit));
        break;
      case TraceApi::packet8:
        packets8_.intersect(scene, context, traced_.data(), n);
        break;
      case TraceApi::packet16:
        packets16_.intersect(scene, context, traced_.data(), n);
        break;
    }
  }

 private:
  static void clear_hit(RTCHit& hit) {
    hit.geomID = kNoHit;
    hit.instID[0] = kNoHit;
  }

  TraceApi api_;
  std::array<std::uint8_t, FrameTracer::kChunk> traced_{};
  std::array<RTCRayHit, FrameTracer::kChunk> rayhits_;
  BlockPackets<8> packets8_;
  BlockPackets<16> packets16_;
};

}  // namespace

std::string_view to_string(TraceApi api) {
  switch (api) {
    case TraceApi::per_ray:
      return "per_ray";
    case TraceApi::stream:
      return "stream";
    case TraceApi::packet8:
      return "packet8";
    case TraceApi::packet16:
      return "packet16";
  }
  return "per_ray";
}

TraceApi widest_native_packet(const EmbreeDevice& device) {
  return rtcGetDeviceProperty(device.get(), RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0
             ? TraceApi::packet16
             : TraceApi::packet8;
}

void FrameTracer::trace(std::span<const PulseRay> rays, std::span<const std::uint8_t> active,
                        std::span<PulseCandidates> candidates) const {
  const auto count = static_cast<unsigned>(rays.size());
  tbb::parallel_for(tbb::blocked_range<unsigned>(0, count, kChunk),
                    [&](const tbb::blocked_range<unsigned>& range) {
                      const FlushDenormalsToZero ftz;
                      for (unsigned begin = range.begin(); begin < range.end(); begin += kChunk) {
                        const unsigned end = std::min(range.end(), begin + kChunk);
                        trace_range(rays, active, candidates, begin, end);
                      }
                    });
}

void FrameTracer::trace_range(std::span<const PulseRay> rays, std::span<const std::uint8_t> active,
                              std::span<PulseCandidates> candidates, unsigned begin,
                              unsigned end) const {
  if (rays.size() != active.size() || rays.size() != candidates.size()) {
    throw Error("engine: rays, active flags and candidate buffers differ in size");
  }
  std::array<unsigned, kChunk> cylinder_prims;
  std::array<CylinderHit, kChunk> cylinder_hits;
  BlockRays block_rays(api_);
  // The block's rays in double, as arrays (the level ground's test and the wire pass's cull).
  RayArrays arrays;
  static_assert(kChunk <= RayArrays::kCapacity);
  // The level ground (EmbreeScene::level_ground): ray i's range to it, NaN for none, beyond the
  // counter's range or no flat terrain, and which triangle holds it.
  const std::vector<TriangleFrame>& level_ground = scene_->level_ground();
  std::array<double, kChunk> ground_m;
  std::array<std::int64_t, kChunk> ground_triangle;
  SurfaceEnergyBatch batch;
  static_assert(kChunk <= SurfaceEnergyBatch::kCapacity);
  const double max_range = timeout_range_m(scene_->receiver().counter);
  const auto tfar = static_cast<float>(max_range);
  // The wire pass over the block's n rays, ray i searched up to arrays.t_max[i]; a ray that misses
  // the wires' bounds up to there is left out (EmbreeScene::wire_bounds): Embree's own test of
  // its root costs a call.
  std::array<std::int64_t, kChunk> meets_wires;
  const auto trace_wires = [&](TraceContext& context, unsigned n) {
    rays_meet_box(scene_->wire_bounds(), arrays, n, meets_wires.data());
    if (block_rays.in_packets()) {
      block_rays.restart_packets(arrays.t_max, meets_wires.data(), n);
    } else {
      for (unsigned i = 0; i < n; ++i) {
        block_rays.restart(i, static_cast<float>(arrays.t_max[i]), meets_wires[i] != 0);
      }
    }
    block_rays.intersect(scene_->wires(), context, n);
  };

  for (unsigned block = begin; block < end; block += kChunk) {
    const unsigned block_end = std::min(end, block + kChunk);
    TraceContext context;
    rtcInitIntersectContext(&context.rtc);
    context.scene = scene_;
    context.rays = rays;
    context.candidates = candidates;
    context.cylinder_prims = cylinder_prims;
    context.cylinder_hits = cylinder_hits;
    context.chunk_begin = block;
    context.max_range_m = max_range;
    context.traversal_only = work_ == TraceWork::traversal_only;

    // Gather the active rays of the block; inactive ones keep empty candidate lists. An active
    // ray's record is cleared in the record loop below, where its first line is written anyway.
    std::array<unsigned, kChunk> ids;
    std::array<float, kChunk> search_to;  // each ray's search end in the solids pass
    unsigned n = 0;
    for (unsigned id = block; id < block_end; ++id) {
      if (active[id] == 0) {
        candidates[id].clear();
        continue;
      }
      ids[n] = id;
      for (int axis = 0; axis < 3; ++axis) {
        arrays.origin[axis][n] = rays[id].origin_enu_m[axis];
        arrays.dir[axis][n] = rays[id].dir_enu[axis];
      }
      cylinder_prims[id - block] = kNoHit;
      ++n;
    }
    // The level ground's range, where it lies within the counter's range (NaN elsewhere, and
    // everywhere when the terrain is not flat): the solids are searched only up to it.
    std::fill_n(arrays.t_max, n, max_range);
    first_triangle_hits(level_ground, arrays, n, ground_m.data(), ground_triangle.data());
    for (unsigned i = 0; i < n; ++i) {
      search_to[i] =
          std::isnan(ground_m[i]) ? tfar : std::min(tfar, EmbreeScene::search_end(ground_m[i]));
    }
    if (block_rays.in_packets()) {
      block_rays.set_packets(arrays, ids, search_to, n);
    } else {
      for (unsigned i = 0; i < n; ++i) block_rays.set(i, rays[ids[i]], ids[i], search_to[i]);
    }

    // Pass 1: the nearest solid (pole, tree, mesh, ground) along each central ray; the angles
    // and energies of the block's hits in one batch.
    block_rays.intersect(scene_->solids(), context, n);
    if (work_ == TraceWork::traversal_only) {
      // The wire pass as far as Embree's own solid hit (else the level ground's search end, where
      // the solids pass stopped), with the same margin and cull.
      for (unsigned i = 0; i < n; ++i) {
        const bool solid = block_rays.hit(i).geomID != kNoHit;
        arrays.t_max[i] = solid ? std::min(tfar, EmbreeScene::search_end(block_rays.tfar(i)))
                                : block_rays.tfar(i);
      }
      for (unsigned i = 0; i < n; ++i) candidates[ids[i]].clear();
      trace_wires(context, n);
      continue;
    }
    batch.clear();
    for (unsigned i = 0; i < n; ++i) {
      const unsigned id = ids[i];
      candidates[id].clear();
      std::optional<TriangleHit> ground;
      if (!std::isnan(ground_m[i])) {
        ground = TriangleHit{ground_m[i], level_ground[ground_triangle[i]].normal};
      }
      record_solid(*scene_, noise_, rays[id], block_rays.hit(i), cylinder_prims[id - block],
                   cylinder_hits[id - block], ground, candidates[id], batch);
    }
    batch.evaluate();
    // Each solid's angle and energy, and, while its candidates are at hand, the ray's search end
    // in pass 2: the wires in front of the solid. The filter offers only segments nearer than the
    // solid hit; tfar reaches a float-safety margin beyond it (EmbreeScene::search_end), so a
    // segment whose closest approach lies before the solid is always reported.
    std::size_t slot = 0;
    for (unsigned i = 0; i < n; ++i) {
      PulseCandidates& pulse = candidates[ids[i]];
      if (!pulse.has_solid()) {
        arrays.t_max[i] = tfar;
        continue;
      }
      pulse.complete_solid(batch.result(slot++));
      arrays.t_max[i] = std::min(tfar, EmbreeScene::search_end(pulse.solid().range_m));
    }
    trace_wires(context, n);
  }
}

}  // namespace owsim
