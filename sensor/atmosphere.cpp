#include "sensor/atmosphere.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {
namespace {

constexpr double kKoschmiederConstant = 3.912;   // ln(1 / 0.02)
constexpr double kVisibilityReferenceUm = 0.55;  // the visibility is defined at 550 nm

}  // namespace

double kim_size_exponent(double visibility_km) {
  if (visibility_km > 50.0) return 1.6;
  if (visibility_km > 6.0) return 1.3;
  if (visibility_km > 1.0) return 0.16 * visibility_km + 0.34;
  if (visibility_km > 0.5) return visibility_km - 0.5;
  return 0.0;
}

double extinction_per_m(const Atmosphere& atmosphere) {
  if (!atmosphere.visibility_km) return 0.0;
  const double visibility_km = *atmosphere.visibility_km;
  const double per_km = kKoschmiederConstant / visibility_km *
                        std::pow(atmosphere.wavelength_um / kVisibilityReferenceUm,
                                 -kim_size_exponent(visibility_km));
  return 1e-3 * per_km;
}

double two_way_transmission(const Atmosphere& atmosphere, double range_m) {
  if (!atmosphere.visibility_km) return atmosphere.transmission;
  return std::exp(-2.0 * extinction_per_m(atmosphere) * std::max(range_m, 0.0));
}

void validate(const Atmosphere& atmosphere) {
  if (!(atmosphere.transmission > 0.0 && atmosphere.transmission <= 1.0)) {
    throw input_error("atmosphere.transmission", "must be a two-way fraction in (0, 1], got " +
                                                     number_text(atmosphere.transmission));
  }
  if (atmosphere.visibility_km &&
      !(std::isfinite(*atmosphere.visibility_km) && *atmosphere.visibility_km > 0.0)) {
    throw input_error("atmosphere.visibility_km",
                      "must be a finite number > 0, got " + number_text(*atmosphere.visibility_km));
  }
  if (!(std::isfinite(atmosphere.wavelength_um) && atmosphere.wavelength_um > 0.0)) {
    throw input_error("atmosphere.wavelength_um",
                      "must be a finite number > 0, got " + number_text(atmosphere.wavelength_um));
  }
}

}  // namespace owsim
