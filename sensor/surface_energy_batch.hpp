#pragma once
// The incidence angle and energy of many solid-surface hits at once (SENSOR-SPEC §7, eq 7.11–7.13):
// the tracer collects what each hit of a chunk contributes — the ray's direction and the surface
// normal, its footprint share, reflectivity and transmission — and evaluates the angles and
// energies over arrays, on vector lanes. Each entry gets exactly the bits of
// `surface_angle_energy` for that one hit.
#include <Eigen/Core>
#include <cstddef>

namespace owsim {

// What one solid hit contributes before its angle is taken.
struct SurfaceTerms {
  Eigen::Vector3d ray_dir = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // either sense
  double footprint_fraction = 1.0;
  double reflectivity = 0.0;
  double transmission = 1.0;
};

struct AngleEnergy {
  double incidence_deg = 0.0;
  double energy_rel = 0.0;
};

// θ = surface_incidence_deg(ray_dir, normal) and energy_rel = fraction · Ref(θ)/Ref(0) · A · T_atm
// (eq 7.11–7.13)
[[nodiscard]] AngleEnergy surface_angle_energy(const SurfaceTerms& terms);

class SurfaceEnergyBatch {
 public:
  static constexpr std::size_t kCapacity = 256;

  void clear() { size_ = 0; }
  // Adds a hit; returns its slot. At most kCapacity between clears.
  std::size_t add(const SurfaceTerms& terms);
  // Fills every slot's angle and energy.
  void evaluate();
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] AngleEnergy result(std::size_t slot) const {
    return {incidence_deg_[slot], energy_rel_[slot]};
  }

 private:
  std::size_t size_ = 0;
  alignas(64) double dir_[3][kCapacity];
  alignas(64) double normal_[3][kCapacity];
  alignas(64) double fraction_[kCapacity];
  alignas(64) double reflectivity_[kCapacity];
  alignas(64) double transmission_[kCapacity];
  alignas(64) double incidence_deg_[kCapacity];
  alignas(64) double energy_rel_[kCapacity];
};

}  // namespace owsim
