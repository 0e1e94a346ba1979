#include "engine/frame_tracer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>

#include "engine/flush_to_zero.hpp"
#include "engine/trace_context.hpp"
#include "geometry/error.hpp"
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

// The nearest solid hit Embree reported, turned into the pulse's solid candidate in double; its
// angle and energy are left to the chunk's batch (the terms go there).
void record_solid(const EmbreeScene& scene, const ReceiverNoise& noise, const PulseRay& ray,
                  const RTCHit& solid, const CylinderRecord& cylinder, PulseCandidates& out,
                  SurfaceEnergyBatch& batch) {
  const unsigned geom_id = solid.geomID, prim_id = solid.primID;
  if (geom_id == kNoHit) return;
  const Scene& objects = scene.scene();
  const ReceiverParams& receiver = scene.receiver();
  const auto set_solid = [&](double range_m, const SurfaceTerms& terms, std::uint32_t object,
                             SurfaceClass surface, const Eigen::Vector3d& normal) {
    out.set_solid(solid_candidate(range_m, {}, object, surface),
                  solid_background(noise, normal, ray, terms.reflectivity));
    batch.add(terms);
  };
  if (geom_id < objects.meshes.size()) {
    const MeshObject& mesh = objects.meshes[geom_id];
    const TriangleHit hit = scene.mesh_hit(geom_id, prim_id, ray);
    set_solid(hit.t, extended_surface_terms(ray, hit.t, hit.normal, mesh.reflectivity, receiver),
              mesh_object_index(objects, geom_id), mesh.surface, hit.normal);
    return;
  }
  if (geom_id == scene.cylinders_geom_id()) {
    if (cylinder.prim_id != prim_id) throw Error("engine: cylinder hit record out of step");
    const Cylinder& hit_cylinder = objects.cylinders[prim_id];
    set_solid(cylinder.hit.t, cylinder_terms(ray, hit_cylinder, cylinder.hit, receiver),
              cylinder_object_index(objects, prim_id), hit_cylinder.surface, cylinder.hit.normal);
    return;
  }
  if (scene.is_terrain(geom_id)) {
    const TriangleHit hit = scene.terrain_hit(solid, ray);
    set_solid(
        hit.t,
        extended_surface_terms(ray, hit.t, hit.normal, objects.terrain.reflectivity, receiver),
        ground_object_index(objects), SurfaceClass::ground, hit.normal);
  }
}

// One Embree query over the block's rays, in the chosen form.
void intersect_block(TraceApi api, RTCScene scene, TraceContext& context, RTCRayHit* rayhits,
                     unsigned n) {
  switch (api) {
    case TraceApi::per_ray:
      for (unsigned i = 0; i < n; ++i) rtcIntersect1(scene, &context.rtc, &rayhits[i]);
      break;
    case TraceApi::stream:
      context.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcIntersect1M(scene, &context.rtc, rayhits, n, sizeof(RTCRayHit));
      break;
    case TraceApi::packet8:
      context.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (unsigned first = 0; first < n; first += 8) {
        alignas(32) RTCRayHit8 packet;
        alignas(32) int valid[8];
        for (unsigned lane = 0; lane < 8; ++lane) {
          const unsigned i = first + lane;
          valid[lane] = i < n ? -1 : 0;
          const RTCRayHit& source = rayhits[i < n ? i : first];
          packet.ray.org_x[lane] = source.ray.org_x;
          packet.ray.org_y[lane] = source.ray.org_y;
          packet.ray.org_z[lane] = source.ray.org_z;
          packet.ray.dir_x[lane] = source.ray.dir_x;
          packet.ray.dir_y[lane] = source.ray.dir_y;
          packet.ray.dir_z[lane] = source.ray.dir_z;
          packet.ray.tnear[lane] = source.ray.tnear;
          packet.ray.tfar[lane] = source.ray.tfar;
          packet.ray.time[lane] = 0.0f;
          packet.ray.mask[lane] = 0xFFFFFFFFu;
          packet.ray.id[lane] = source.ray.id;
          packet.ray.flags[lane] = 0;
          packet.hit.geomID[lane] = kNoHit;
          packet.hit.instID[0][lane] = kNoHit;
        }
        rtcIntersect8(valid, scene, &context.rtc, &packet);
        for (unsigned lane = 0; lane < 8 && first + lane < n; ++lane) {
          RTCRayHit& target = rayhits[first + lane];
          target.ray.tfar = packet.ray.tfar[lane];
          target.hit.geomID = packet.hit.geomID[lane];
          target.hit.primID = packet.hit.primID[lane];
          target.hit.u = packet.hit.u[lane];
          target.hit.v = packet.hit.v[lane];
        }
      }
      break;
  }
}

}  // namespace

std::string_view to_string(TraceApi api) {
  switch (api) {
    case TraceApi::per_ray:
      return "per_ray";
    case TraceApi::stream:
      return "stream";
    case TraceApi::packet8:
      return "packet8";
  }
  return "per_ray";
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
  std::array<CylinderRecord, kChunk> cylinder_hits;
  std::array<RTCRayHit, kChunk> rayhits;
  SurfaceEnergyBatch batch;
  static_assert(kChunk <= SurfaceEnergyBatch::kCapacity);
  const double max_range = timeout_range_m(scene_->receiver().counter);
  const auto tfar = static_cast<float>(max_range);

  for (unsigned block = begin; block < end; block += kChunk) {
    const unsigned block_end = std::min(end, block + kChunk);
    TraceContext context;
    rtcInitIntersectContext(&context.rtc);
    context.scene = scene_;
    context.rays = rays;
    context.candidates = candidates;
    context.cylinder_hits = cylinder_hits;
    context.chunk_begin = block;
    context.max_range_m = max_range;
    context.traversal_only = work_ == TraceWork::traversal_only;

    // Gather the active rays of the block; inactive ones keep empty candidate lists.
    unsigned n = 0;
    for (unsigned id = block; id < block_end; ++id) {
      candidates[id].clear();
      if (active[id] == 0) continue;
      set_ray(rayhits[n].ray, rays[id], id, tfar);
      rayhits[n].hit.geomID = kNoHit;
      rayhits[n].hit.instID[0] = kNoHit;
      cylinder_hits[id - block].prim_id = kNoHit;
      ++n;
    }

    // Pass 1: the nearest solid (pole, tree, mesh, ground) along each central ray; the angles
    // and energies of the block's hits in one batch.
    intersect_block(api_, scene_->solids(), context, rayhits.data(), n);
    if (work_ == TraceWork::traversal_only) {
      // The wire pass as far as Embree's own solid hit, with the same margin.
      for (unsigned i = 0; i < n; ++i) {
        const unsigned id = rayhits[i].ray.id;
        const bool solid = rayhits[i].hit.geomID != kNoHit;
        const float wire_tfar =
            solid ? std::min(tfar, EmbreeScene::wire_search_end(rayhits[i].ray.tfar)) : tfar;
        set_ray(rayhits[i].ray, rays[id], id, wire_tfar);
        rayhits[i].hit.geomID = kNoHit;
        rayhits[i].hit.instID[0] = kNoHit;
      }
      intersect_block(api_, scene_->wires(), context, rayhits.data(), n);
      continue;
    }
    batch.clear();
    for (unsigned i = 0; i < n; ++i) {
      const RTCRayHit& rayhit = rayhits[i];
      const unsigned id = rayhit.ray.id;
      record_solid(*scene_, noise_, rays[id], rayhit.hit, cylinder_hits[id - block], candidates[id],
                   batch);
    }
    batch.evaluate();
    std::size_t slot = 0;
    for (unsigned i = 0; i < n; ++i) {
      PulseCandidates& pulse = candidates[rayhits[i].ray.id];
      if (pulse.has_solid()) pulse.complete_solid(batch.result(slot++));
    }

    // Pass 2: the wires in front of it. The filter offers only segments nearer than the solid
    // hit; tfar reaches a float-safety margin beyond it (EmbreeScene::wire_search_end), so a
    // segment whose closest approach lies before the solid is always reported.
    for (unsigned i = 0; i < n; ++i) {
      const unsigned id = rayhits[i].ray.id;
      const PulseCandidates& pulse = candidates[id];
      const float wire_tfar =
          pulse.has_solid() ? std::min(tfar, EmbreeScene::wire_search_end(pulse.solid().range_m))
                            : tfar;
      set_ray(rayhits[i].ray, rays[id], id, wire_tfar);
      rayhits[i].hit.geomID = kNoHit;
      rayhits[i].hit.instID[0] = kNoHit;
    }
    intersect_block(api_, scene_->wires(), context, rayhits.data(), n);
  }
}

}  // namespace owsim
