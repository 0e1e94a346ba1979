#pragma once
// What every surface of the scene contributes to one pulse (SENSOR-SPEC §7 "Pinned per surface",
// "Pinned occlusion"), shared by the Embree tracer and the brute-force reference tracer so both
// apply the very same double-precision rules:
//   wire   — a candidate when the ray passes within r_wire + r_beam(R) of the segment's axis,
//            R the range to the closest approach; one candidate per conductor, its
//            highest-energy segment among those in front of the solid hit (the tracers offer
//            only those).
//   pole / tree — the central ray's hit on the cylinder; footprint from the ray–axis distance.
//   ground, mesh — the central ray's hit; footprint 1, incidence from the triangle's normal.
// The central ray stops at the nearest solid surface (pole, tree, mesh, ground) whether or not that
// surface's echo reaches the threshold; wires beyond it are dropped, wires never occlude.
//
// Object indices: conductors 0..C−1, cylinders C..C+Y−1, meshes C+Y..C+Y+M−1, the ground C+Y+M
// (named_object_count, geometry/scene.hpp).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>

#include "geometry/cylinder.hpp"
#include "geometry/scene.hpp"
#include "sensor/receiver.hpp"
#include "sensor/surface_energy_batch.hpp"

namespace owsim {

// One pulse's central ray in the scenario's local ENU frame (double; dir has unit length).
struct PulseRay {
  Eigen::Vector3d origin_enu_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d dir_enu = Eigen::Vector3d::UnitY();
};

[[nodiscard]] inline std::uint32_t cylinder_object_index(const Scene& scene, std::size_t cylinder) {
  return static_cast<std::uint32_t>(scene.conductors.size() + cylinder);
}
[[nodiscard]] inline std::uint32_t mesh_object_index(const Scene& scene, std::size_t mesh) {
  return static_cast<std::uint32_t>(scene.conductors.size() + scene.cylinders.size() + mesh);
}
[[nodiscard]] inline std::uint32_t ground_object_index(const Scene& scene) {
  return static_cast<std::uint32_t>(named_object_count(scene));
}

// The candidate a wire segment gives, if the beam touches it  (SENSOR-SPEC §7, eq 7.1–7.13)
[[nodiscard]] bool wire_segment_candidate(const PulseRay& ray, const Conductor& conductor,
                                          std::size_t segment, std::uint32_t object,
                                          const ReceiverParams& receiver, Candidate& out);
// What a central-ray hit on a pole or tree contributes before its angle is taken: the angle to
// the hit's normal, the footprint share on the cylinder, its reflectivity and T_atm
// (SENSOR-SPEC §7 pinned per surface)
[[nodiscard]] SurfaceTerms cylinder_terms(const PulseRay& ray, const Cylinder& cylinder,
                                          const CylinderHit& hit, const ReceiverParams& receiver);
// The same for a central-ray hit on an extended surface (ground, mesh): footprint 1
[[nodiscard]] SurfaceTerms extended_surface_terms(const PulseRay& ray, double range_m,
                                                  const Eigen::Vector3d& normal,
                                                  double reflectivity,
                                                  const ReceiverParams& receiver);
// A solid hit's candidate from its range, angle and energy (surface_angle_energy or a batch)
[[nodiscard]] Candidate solid_candidate(double range_m, const AngleEnergy& angle_energy,
                                        std::uint32_t object, SurfaceClass surface);

// The candidate of a central-ray hit on a pole or tree  (SENSOR-SPEC §7 pinned per surface)
[[nodiscard]] Candidate cylinder_candidate(const PulseRay& ray, const Cylinder& cylinder,
                                           const CylinderHit& hit, std::uint32_t object,
                                           const ReceiverParams& receiver);
// The candidate of a central-ray hit on the ground  (SENSOR-SPEC §7 pinned per surface)
[[nodiscard]] Candidate ground_candidate(const PulseRay& ray, double range_m,
                                         const Eigen::Vector3d& normal, double reflectivity,
                                         std::uint32_t object, const ReceiverParams& receiver);
// The candidate of a central-ray hit on a mesh's triangle: an extended surface like the ground
// (SENSOR-SPEC §7 pinned per surface), of the mesh's class.
[[nodiscard]] Candidate mesh_candidate(const PulseRay& ray, double range_m,
                                       const Eigen::Vector3d& normal, const MeshObject& mesh,
                                       std::uint32_t object, const ReceiverParams& receiver);

// The candidates one pulse collects while it is traced: at most kMaxWires conductors (the
// strongest kept when more are met) and the nearest solid hit. Fixed size: no allocation.
// Cache-line aligned with the solid hit, its background and the counts first: the trace's
// clear and set_solid and the receiver's sorting of a pulse touch that one line, and the wires'
// lines only when the pulse met a wire.
class alignas(64) PulseCandidates {
 public:
  static constexpr int kMaxWires = 8;

  void clear() {
    wire_count_ = 0;
    has_solid_ = false;
  }
  // A wire segment's candidate: kept if it is its conductor's strongest so far.
  void offer_wire(const Candidate& candidate);
  // The nearest solid surface the central ray hit (the caller guarantees it is the nearest), and
  // the sunlight background b it scatters into the receiver (SENSOR-SPEC §11; 0 at night).
  void set_solid(const Candidate& candidate, double background = 0.0) {
    solid_ = candidate;
    solid_background_ = background;
    has_solid_ = true;
  }
  // The solid hit's angle and energy, when set_solid was given its range, object and class only
  // (the tracer evaluates a chunk's angles in one batch).
  void complete_solid(const AngleEnergy& angle_energy) {
    solid_.incidence_deg = angle_energy.incidence_deg;
    solid_.energy_rel = angle_energy.energy_rel;
  }
  [[nodiscard]] bool has_solid() const { return has_solid_; }
  [[nodiscard]] const Candidate& solid() const { return solid_; }
  [[nodiscard]] double solid_background() const { return solid_background_; }
  [[nodiscard]] std::span<const Candidate> wires() const {
    return {wires_.data(), static_cast<std::size_t>(wire_count_)};
  }
  // The candidates the receiver sees: wires nearer than the solid hit, then the solid hit.
  // Returns the used prefix of `out`, which holds at least kMaxWires + 1.
  std::span<Candidate> gather(std::span<Candidate> out) const;

 private:
  Candidate solid_{};
  double solid_background_ = 0.0;
  int wire_count_ = 0;
  bool has_solid_ = false;
  std::array<Candidate, kMaxWires> wires_{};
};

}  // namespace owsim
