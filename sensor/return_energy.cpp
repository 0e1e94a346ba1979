#include "sensor/return_energy.hpp"

#include "sensor/footprint.hpp"

namespace owsim {

bool beam_touches_wire(double distance_m, double range_m, double wire_radius_m,
                       const BeamParams& beam) {
  return distance_m < wire_radius_m + beam_radius_m(range_m, beam);
}

ReturnEnergy wire_return_energy(double distance_m, double range_m, double wire_radius_m,
                                double incidence_deg, double reflectivity, const BeamParams& beam,
                                const Atmosphere& atmosphere) {
  if (!beam_touches_wire(distance_m, range_m, wire_radius_m, beam)) return {};
  const double beam_radius = beam_radius_m(range_m, beam);
  ReturnEnergy result;
  result.candidate = true;
  result.footprint_fraction = footprint_fraction(distance_m, wire_radius_m, beam_radius);
  result.energy_rel = energy_rel(result.footprint_fraction, incidence_deg, reflectivity,
                                 two_way_transmission(atmosphere, range_m));
  return result;
}

double cylinder_footprint_fraction(double axis_distance_m, double range_m, double cylinder_radius_m,
                                   const BeamParams& beam) {
  const double beam_radius = beam_radius_m(range_m, beam);
  return axis_distance_m + beam_radius <= cylinder_radius_m
             ? 1.0
             : footprint_fraction(axis_distance_m, cylinder_radius_m, beam_radius);
}

ReturnEnergy cylinder_return_energy(double axis_distance_m, double range_m,
                                    double cylinder_radius_m, double incidence_deg,
                                    double reflectivity, const BeamParams& beam,
                                    const Atmosphere& atmosphere) {
  ReturnEnergy result;
  result.candidate = axis_distance_m <= cylinder_radius_m;
  result.footprint_fraction =
      cylinder_footprint_fraction(axis_distance_m, range_m, cylinder_radius_m, beam);
  result.energy_rel = energy_rel(result.footprint_fraction, incidence_deg, reflectivity,
                                 two_way_transmission(atmosphere, range_m));
  return result;
}

ReturnEnergy ground_return_energy(double range_m, double incidence_deg, double reflectivity,
                                  const Atmosphere& atmosphere) {
  ReturnEnergy result;
  result.candidate = true;
  result.footprint_fraction = 1.0;
  result.energy_rel =
      energy_rel(1.0, incidence_deg, reflectivity, two_way_transmission(atmosphere, range_m));
  return result;
}

}  // namespace owsim
