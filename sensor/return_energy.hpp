#pragma once
// Received / transmitted pulse energy for one surface the beam meets (SENSOR-SPEC §7, eq 7.13 and
// "Pinned per surface"):
//   energy_rel = ξ_rx / ξ_tx = (a_fp / a_ls) · (Ref(θ) / Ref(0)) · A · T_atm
// with a_fp / a_ls the covered share of the beam disc (sensor/footprint.hpp), Ref the angular
// reflectivity (sensor/reflectivity.hpp), A the object's reflectivity (0..1) and T_atm the two-way
// transmission (sensor/atmosphere.hpp). One model for wires, poles, trees and ground, so one
// threshold decides every return. No range-squared loss: the source's ratio is geometric only.
// Valid for ranges ≥ 0 and A in [0, 1]; the result is then in [0, 1].
#include "sensor/atmosphere.hpp"
#include "sensor/beam.hpp"
#include "sensor/reflectivity.hpp"

namespace owsim {

// The receiver's view of one object on one pulse.
struct ReturnEnergy {
  bool candidate = false;           // the beam meets the object by the §7 rule for its surface
  double footprint_fraction = 0.0;  // a_fp / a_ls, in [0, 1]
  double energy_rel = 0.0;          // ξ_rx / ξ_tx
};

// (a_fp / a_ls) · (Ref(θ) / 40) · A · T_atm  (SENSOR-SPEC §7, eq 7.13); inline, for array loops
[[nodiscard]] inline double energy_rel(double footprint_fraction, double incidence_deg,
                                       double reflectivity, double transmission) {
  return footprint_fraction * (reflectivity_pct(incidence_deg) / kReflectivityNormalPct) *
         reflectivity * transmission;
}

// Whether the beam touches a wire: the closest-approach distance d < r_wire + r_beam(R), R the
// range along the ray to the closest approach (SENSOR-SPEC §7, closest approach eq 7.1–7.7)
[[nodiscard]] bool beam_touches_wire(double distance_m, double range_m, double wire_radius_m,
                                     const BeamParams& beam);

// Wire: candidate when the closest-approach distance d < r_wire + r_beam(R), R the range along
// the ray to the closest approach; fraction = circle–strip(d, r_wire, r_beam(R)) / (π r_beam²);
// zeros when not a candidate
// (SENSOR-SPEC §7 pinned per surface, eq 7.1–7.13)
[[nodiscard]] ReturnEnergy wire_return_energy(double distance_m, double range_m,
                                              double wire_radius_m, double incidence_deg,
                                              double reflectivity, const BeamParams& beam,
                                              const Atmosphere& atmosphere);
// Pole / tree: candidate when the central ray meets the silhouette, d ≤ r_cyl (d the ray–axis
// distance; 0 for a hit on the top cap); fraction 1 when the whole beam lies on it
// (d + r_beam ≤ r_cyl), else circle–strip(d, r_cyl, r_beam) / (π r_beam²). The energy is given
// for any d — the share is continuous — so a wall hit that rounding puts a hair outside r_cyl
// still gets its (about half-beam) energy  (SENSOR-SPEC §7 pinned per surface)
[[nodiscard]] double cylinder_footprint_fraction(double axis_distance_m, double range_m,
                                                 double cylinder_radius_m, const BeamParams& beam);
[[nodiscard]] ReturnEnergy cylinder_return_energy(double axis_distance_m, double range_m,
                                                  double cylinder_radius_m, double incidence_deg,
                                                  double reflectivity, const BeamParams& beam,
                                                  const Atmosphere& atmosphere);
// Ground: the central ray's hit, fraction 1, always a candidate  (SENSOR-SPEC §7 pinned per
// surface)
[[nodiscard]] ReturnEnergy ground_return_energy(double range_m, double incidence_deg,
                                                double reflectivity, const Atmosphere& atmosphere);

}  // namespace owsim
