#include "sensor/surface_energy_batch.hpp"

#include "geometry/error.hpp"
#include "geometry/vector_clones.hpp"
#include "sensor/reflectivity.hpp"
#include "sensor/return_energy.hpp"

namespace owsim {
namespace {

// This file is compiled with -fno-trapping-math (CMakeLists.txt): GCC may then turn the angle's
// and the reflectivity's choices into selects and run the loop on vector lanes. The values are the
// same; only floating-point exception flags, which owsim never reads, could differ.
OWSIM_VECTOR_CLONES void evaluate_arrays(
    std::size_t n, const double* __restrict dx, const double* __restrict dy,
    const double* __restrict dz, const double* __restrict nx, const double* __restrict ny,
    const double* __restrict nz, const double* __restrict fraction,
    const double* __restrict reflectivity, const double* __restrict transmission,
    double* __restrict incidence_deg, double* __restrict energy) {
  for (std::size_t i = 0; i < n; ++i) {
    const double theta = surface_incidence_deg(dx[i], dy[i], dz[i], nx[i], ny[i], nz[i]);
    incidence_deg[i] = theta;
    energy[i] = energy_rel(fraction[i], theta, reflectivity[i], transmission[i]);
  }
}

}  // namespace

AngleEnergy surface_angle_energy(const SurfaceTerms& terms) {
  const double theta = surface_incidence_deg(terms.ray_dir, terms.normal);
  return {theta,
          energy_rel(terms.footprint_fraction, theta, terms.reflectivity, terms.transmission)};
}

std::size_t SurfaceEnergyBatch::add(const SurfaceTerms& terms) {
  if (size_ == kCapacity) throw Error("surface energy batch: more hits than its capacity");
  const std::size_t slot = size_++;
  for (int axis = 0; axis < 3; ++axis) {
    dir_[axis][slot] = terms.ray_dir[axis];
    normal_[axis][slot] = terms.normal[axis];
  }
  fraction_[slot] = terms.footprint_fraction;
  reflectivity_[slot] = terms.reflectivity;
  transmission_[slot] = terms.transmission;
  return slot;
}

void SurfaceEnergyBatch::evaluate() {
  evaluate_arrays(size_, dir_[0], dir_[1], dir_[2], normal_[0], normal_[1], normal_[2], fraction_,
                  reflectivity_, transmission_, incidence_deg_, energy_rel_);
}

}  // namespace owsim
