#pragma once
// The transmitted beam's radius along its path (SENSOR-SPEC §7): a cone of full divergence angle
// from an exit aperture, r_beam(R) = r_exit + R·tan(divergence/2). Geometric optics, no Gaussian
// profile (the footprint model of §7 treats the beam as a uniform disc). Valid for R ≥ 0 and a
// divergence below π rad; exact to rounding. validate(ReceiverParams) checks the fields.
namespace owsim {

struct BeamParams {
  double divergence_mrad = 1.0;  // §7 full angle (scenario key sensor.divergence_mrad)
  double exit_radius_m = 0.0;    // §7 r_exit (scenario key sensor.beam_exit_radius_m)
};

// r_beam(R) = r_exit + R·tan(divergence / 2)  (SENSOR-SPEC §7)
[[nodiscard]] double beam_radius_m(double range_m, const BeamParams& beam);

}  // namespace owsim
