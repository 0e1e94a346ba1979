#pragma once
// Two-way atmospheric transmission of the laser pulse (SENSOR-SPEC §7, eq 7.13 factor T_atm).
//
// The source uses one constant percentage (ch. 7); that is the default (`transmission`, two-way).
// With a meteorological visibility V (km) the transmission follows the range instead, from the
// Kruse visibility law with Kim's size-distribution exponent q (Kruse, McGlauchlin & McQuistan,
// "Elements of Infrared Technology", 1962; Kim, McArthur & Korevaar, "Comparison of laser beam
// propagation at 785 nm and 1550 nm in fog and haze for optical wireless communications",
// Proc. SPIE 4214, 2001):
//   σ = (3.912 / V) · (λ / 0.55 µm)^(−q)   [1/km; 3.912 = ln 50, Koschmieder's 2 % contrast]
//   q = 1.6 (V > 50 km), 1.3 (6 < V ≤ 50), 0.16·V + 0.34 (1 < V ≤ 6), V − 0.5 (0.5 < V ≤ 1),
//       0 (V ≤ 0.5)
//   T = exp(−2·σ·R)  (out and back over the range R).
// Valid for haze and fog of uniform density along the path (no rain or snow model) and λ of
// roughly 0.4–2 µm; the law is an empirical fit, good to some tens of percent in σ.
#include <optional>

namespace owsim {

struct Atmosphere {
  double transmission =
      0.95;  // two-way, used when no visibility is given (key atmosphere.transmission)
  std::optional<double>
      visibility_km;           // meteorological visibility V (key atmosphere.visibility_km)
  double wavelength_um = 1.5;  // §1 laser wavelength λ (key atmosphere.wavelength_um)
};

// Kim's exponent q(V)  (Kim et al. 2001)
[[nodiscard]] double kim_size_exponent(double visibility_km);
// Extinction coefficient σ in 1/m from the Kruse/Kim law; 0 when no visibility is given
[[nodiscard]] double extinction_per_m(const Atmosphere& atmosphere);
// T_atm: the constant without visibility, else exp(−2·σ·R); a negative range counts as 0
// (SENSOR-SPEC §7, eq 7.13)
[[nodiscard]] double two_way_transmission(const Atmosphere& atmosphere, double range_m);

// Throws owsim::Error naming the key for: a transmission outside (0, 1], a visibility that is
// not a finite number > 0, a wavelength that is not a finite number > 0.
void validate(const Atmosphere& atmosphere);

}  // namespace owsim
