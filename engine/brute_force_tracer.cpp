#include "engine/brute_force_tracer.hpp"

#include <optional>

#include "geometry/cylinder.hpp"
#include "geometry/error.hpp"
#include "geometry/ray_triangle.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {

void BruteForceTracer::trace(const PulseRay& ray, PulseCandidates& out) const {
  out.clear();
  const Scene& scene = *scene_;
  const double max_range = timeout_range_m(receiver_.counter);

  // The nearest solid surface along the central ray; on equal ranges the first found (the lower
  // cylinder index, cylinders before meshes before the ground) stays.
  double nearest = max_range;
  std::optional<Candidate> solid;
  for (std::size_t c = 0; c < scene.cylinders.size(); ++c) {
    const auto hit = intersect(scene.cylinders[c], ray.origin_enu_m, ray.dir_enu, 0.0, nearest);
    if (!hit || (solid && hit->t == nearest)) continue;
    nearest = hit->t;
    solid = cylinder_candidate(ray, scene.cylinders[c], *hit, cylinder_object_index(scene, c),
                               receiver_);
  }
  const auto triangles_in_front = [&](const TriangleMesh& mesh, const auto& candidate_of) {
    for (const auto& triangle : mesh.triangles) {
      const auto hit =
          intersect_triangle(ray.origin_enu_m, ray.dir_enu, mesh.vertices[triangle[0]],
                             mesh.vertices[triangle[1]], mesh.vertices[triangle[2]], 0.0, nearest);
      if (!hit || (solid && hit->t == nearest)) continue;
      nearest = hit->t;
      solid = candidate_of(*hit);
    }
  };
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    triangles_in_front(scene.meshes[m].mesh, [&](const TriangleHit& hit) {
      return mesh_candidate(ray, hit.t, hit.normal, scene.meshes[m], mesh_object_index(scene, m),
                            receiver_);
    });
  }
  triangles_in_front(terrain_mesh_, [&](const TriangleHit& hit) {
    return ground_candidate(ray, hit.t, hit.normal, scene.terrain.reflectivity,
                            ground_object_index(scene), receiver_);
  });
  if (solid) out.set_solid(*solid);

  // Every segment of every conductor in front of the solid hit: the central ray never reaches
  // the ones behind it, so a conductor's candidate is its strongest visible segment.
  for (std::size_t w = 0; w < scene.conductors.size(); ++w) {
    const Conductor& conductor = scene.conductors[w];
    for (std::size_t s = 0; s + 1 < conductor.points_enu_m.size(); ++s) {
      Candidate candidate;
      if (wire_segment_candidate(ray, conductor, s, static_cast<std::uint32_t>(w), receiver_,
                                 candidate) &&
          candidate.range_m <= max_range && (!solid || candidate.range_m < solid->range_m)) {
        out.offer_wire(candidate);
      }
    }
  }
}

void BruteForceTracer::trace(std::span<const PulseRay> rays, std::span<const std::uint8_t> active,
                             std::span<PulseCandidates> candidates) const {
  if (rays.size() != active.size() || rays.size() != candidates.size()) {
    throw Error("engine: rays, active flags and candidate buffers differ in size");
  }
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (active[i] != 0) {
      trace(rays[i], candidates[i]);
    } else {
      candidates[i].clear();
    }
  }
}

}  // namespace owsim
