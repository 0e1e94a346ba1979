#pragma once
// Angular reflectivity of a wire (SENSOR-SPEC §7, source eq 7.11–7.12) and the incidence angles
// it is evaluated at.
//
// The source fits measured wire returns against the incidence angle θ to the surface normal with
// a quartic on 0°..45° and a straight line from Ref(45°) = 8.07 % down to 0 at 90°:
//   Ref(θ) = 9.3e-6·θ⁴ − 0.00064·θ³ − 0.0058·θ² + 40  (percent, θ in degrees).
// Ref(0) = 40 %, Ref(30) = 25.03 %, Ref(45) = 8.07 %; monotonic decreasing on 0°..90°. The curve
// is symmetric in θ and 0 beyond 90°. §7 Decision: the same curve, divided by Ref(0), scales the
// return of poles, trees and ground too. Accuracy: that of the source's fit (a few percent).
#include <Eigen/Core>

namespace owsim {

inline constexpr double kReflectivityNormalPct = 40.0;  // Ref(0), eq 7.12

// Ref(θ) in percent, |θ| used, 0 for |θ| ≥ 90°  (SENSOR-SPEC §7, eq 7.12)
[[nodiscard]] double reflectivity_pct(double incidence_deg);
// θ = 90° − angle(ray, wire axis), the acute angle, in [0°, 90°]  (SENSOR-SPEC §7, eq 7.11)
[[nodiscard]] double wire_incidence_deg(const Eigen::Vector3d& ray_dir,
                                        const Eigen::Vector3d& wire_axis);
// θ = angle between −ray and the surface normal in [0°, 90°]; either orientation of the normal
// gives the same angle  (SENSOR-SPEC §7 pinned per surface)
[[nodiscard]] double surface_incidence_deg(const Eigen::Vector3d& ray_dir,
                                           const Eigen::Vector3d& normal);

}  // namespace owsim
