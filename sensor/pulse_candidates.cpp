#include "sensor/pulse_candidates.hpp"

#include <algorithm>

#include "geometry/ray_segment.hpp"
#include "sensor/reflectivity.hpp"
#include "sensor/return_energy.hpp"

namespace owsim {

bool wire_segment_candidate(const PulseRay& ray, const Conductor& conductor, std::size_t segment,
                            std::uint32_t object, const ReceiverParams& receiver, Candidate& out) {
  const Eigen::Vector3d& p0 = conductor.points_enu_m[segment];
  const Eigen::Vector3d& p1 = conductor.points_enu_m[segment + 1];
  const RaySegmentApproach approach = closest_approach(ray.origin_enu_m, ray.dir_enu, p0, p1);
  // The beam's cone first: a segment it cannot touch costs no angles.
  if (!beam_touches_wire(approach.distance_m, approach.ray_t, conductor.radius_m, receiver.beam)) {
    return false;
  }
  const double incidence = wire_incidence_deg(ray.dir_enu, p1 - p0);
  const ReturnEnergy energy =
      wire_return_energy(approach.distance_m, approach.ray_t, conductor.radius_m, incidence,
                         conductor.reflectivity, receiver.beam, receiver.atmosphere);
  if (!energy.candidate) return false;
  out = Candidate{approach.ray_t, energy.energy_rel, incidence, object,
                  static_cast<std::uint8_t>(SurfaceClass::wire)};
  return true;
}

Candidate cylinder_candidate(const PulseRay& ray, const Cylinder& cylinder, const CylinderHit& hit,
                             std::uint32_t object, const ReceiverParams& receiver) {
  const double incidence = surface_incidence_deg(ray.dir_enu, hit.normal);
  // A hit on the top cap sees a disc, not a strip: the whole beam counts when it lies inside.
  const double axis_distance = hit.face == CylinderFace::wall ? hit.axis_distance_m : 0.0;
  const ReturnEnergy energy =
      cylinder_return_energy(axis_distance, hit.t, cylinder.radius_m, incidence,
                             cylinder.reflectivity, receiver.beam, receiver.atmosphere);
  return Candidate{hit.t, energy.energy_rel, incidence, object,
                   static_cast<std::uint8_t>(cylinder.surface)};
}

namespace {

// A central-ray hit on an extended surface: the whole footprint on it (SENSOR-SPEC §7).
Candidate extended_surface_candidate(const PulseRay& ray, double range_m,
                                     const Eigen::Vector3d& normal, double reflectivity,
                                     SurfaceClass surface, std::uint32_t object,
                                     const ReceiverParams& receiver) {
  const double incidence = surface_incidence_deg(ray.dir_enu, normal);
  const ReturnEnergy energy =
      ground_return_energy(range_m, incidence, reflectivity, receiver.atmosphere);
  return Candidate{range_m, energy.energy_rel, incidence, object,
                   static_cast<std::uint8_t>(surface)};
}

}  // namespace

Candidate ground_candidate(const PulseRay& ray, double range_m, const Eigen::Vector3d& normal,
                           double reflectivity, std::uint32_t object,
                           const ReceiverParams& receiver) {
  return extended_surface_candidate(ray, range_m, normal, reflectivity, SurfaceClass::ground,
                                    object, receiver);
}

Candidate mesh_candidate(const PulseRay& ray, double range_m, const Eigen::Vector3d& normal,
                         const MeshObject& mesh, std::uint32_t object,
                         const ReceiverParams& receiver) {
  return extended_surface_candidate(ray, range_m, normal, mesh.reflectivity, mesh.surface, object,
                                    receiver);
}

void PulseCandidates::offer_wire(const Candidate& candidate) {
  for (int i = 0; i < wire_count_; ++i) {
    Candidate& kept = wires_[static_cast<std::size_t>(i)];
    if (kept.object_index != candidate.object_index) continue;
    // The conductor's highest-energy segment; equal energies keep the nearer (order-free).
    if (candidate.energy_rel > kept.energy_rel ||
        (candidate.energy_rel == kept.energy_rel && candidate.range_m < kept.range_m)) {
      kept = candidate;
    }
    return;
  }
  if (wire_count_ < kMaxWires) {
    wires_[static_cast<std::size_t>(wire_count_++)] = candidate;
    return;
  }
  auto weakest = std::min_element(wires_.begin(), wires_.end(), [](const auto& a, const auto& b) {
    return a.energy_rel < b.energy_rel;
  });
  if (candidate.energy_rel > weakest->energy_rel) *weakest = candidate;
}

std::span<Candidate> PulseCandidates::gather(std::span<Candidate> out) const {
  std::size_t n = 0;
  for (int i = 0; i < wire_count_; ++i) {
    const Candidate& wire = wires_[static_cast<std::size_t>(i)];
    if (!has_solid_ || wire.range_m < solid_.range_m) out[n++] = wire;
  }
  if (has_solid_) out[n++] = solid_;
  return {out.data(), n};
}

}  // namespace owsim
