#include "sensor/beam.hpp"

#include <cmath>

namespace owsim {

double beam_radius_m(double range_m, const BeamParams& beam) {
  return beam.exit_radius_m + range_m * std::tan(0.5e-3 * beam.divergence_mrad);
}

}  // namespace owsim
