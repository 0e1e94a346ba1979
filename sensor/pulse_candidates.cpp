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

SurfaceTerms cylinder_terms(const PulseRay& ray, const Cylinder& cylinder, const CylinderHit& hit,
                            const ReceiverParams& receiver) {
  // A hit on the top cap sees a disc, not a strip: the whole beam counts when it lies inside.
  const double axis_distance = hit.face == CylinderFace::wall ? hit.axis_distance_m : 0.0;
  return SurfaceTerms{
      ray.dir_enu, hit.normal,
      cylinder_footprint_fraction(axis_distance, hit.t, cylinder.radius_m, receiver.beam),
      cylinder.reflectivity, two_way_transmission(receiver.atmosphere, hit.t)};
}

SurfaceTerms extended_surface_terms(const PulseRay& ray, double range_m,
                                    const Eigen::Vector3d& normal, double reflectivity,
                                    const ReceiverParams& receiver) {
  return SurfaceTerms{ray.dir_enu, normal, 1.0, reflectivity,
                      two_way_transmission(receiver.atmosphere, range_m)};
}

Candidate solid_candidate(double range_m, const AngleEnergy& angle_energy, std::uint32_t object,
                          SurfaceClass surface) {
  return Candidate{range_m, angle_energy.energy_rel, angle_energy.incidence_deg, object,
                   static_cast<std::uint8_t>(surface)};
}

Candidate cylinder_candidate(const PulseRay& ray, const Cylinder& cylinder, const CylinderHit& hit,
                             std::uint32_t object, const ReceiverParams& receiver) {
  return solid_candidate(hit.t, surface_angle_energy(cylinder_terms(ray, cylinder, hit, receiver)),
                         object, cylinder.surface);
}

Candidate ground_candidate(const PulseRay& ray, double range_m, const Eigen::Vector3d& normal,
                           double reflectivity, std::uint32_t object,
                           const ReceiverParams& receiver) {
  return solid_candidate(
      range_m,
      surface_angle_energy(extended_surface_terms(ray, range_m, normal, reflectivity, receiver)),
      object, SurfaceClass::ground);
}

Candidate mesh_candidate(const PulseRay& ray, double range_m, const Eigen::Vector3d& normal,
                         const MeshObject& mesh, std::uint32_t object,
                         const ReceiverParams& receiver) {
  return solid_candidate(range_m,
                         surface_angle_energy(extended_surface_terms(ray, range_m, normal,
                                                                     mesh.reflectivity, receiver)),
                         object, mesh.surface);
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
