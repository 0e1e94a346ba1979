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
//
// Both are inline and free of branches: the engine evaluates them over arrays of hits on vector
// lanes (sensor/surface_energy_batch.hpp), and a single hit anywhere else gets the same bits.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace owsim {

inline constexpr double kReflectivityNormalPct = 40.0;  // Ref(0), eq 7.12

// The quartic of eq 7.12, valid on 0°..45°.
[[nodiscard]] constexpr double reflectivity_fit_pct(double theta_deg) {
  return (((9.3e-6 * theta_deg - 0.00064) * theta_deg - 0.0058) * theta_deg) * theta_deg +
         kReflectivityNormalPct;
}

// Ref(θ) in percent, |θ| used, 0 for |θ| ≥ 90° and NaN  (SENSOR-SPEC §7, eq 7.12)
[[nodiscard]] inline double reflectivity_pct(double incidence_deg) {
  // Every branch is computed and one chosen: no control flow, so loops over hits vectorise.
  const double theta = std::abs(incidence_deg);
  const double fit = reflectivity_fit_pct(theta);
  const double line = reflectivity_fit_pct(45.0) * (90.0 - theta) / 45.0;
  const double beyond = theta < 90.0 ? line : 0.0;
  return theta <= 45.0 ? fit : beyond;
}

// atan2(opposite, adjacent) in degrees for opposite, adjacent ≥ 0: the acute angle of a right
// triangle, in [0°, 90°]; 0 when both are 0  (SENSOR-SPEC §7, eq 7.11). Moshier's Cephes atan:
// the ratio is reduced to [0, 0.66] (through π/4 + atan((y − x)/(y + x)) up to tan 3π/8, and
// π/2 − atan(x/y) beyond), where a rational function of degree 4/5 in t² is good to 2e-16; within
// 2 ulp of the C library's atan2, at a fraction of its cost, and on vector lanes.
[[nodiscard]] inline double acute_angle_deg(double opposite, double adjacent) {
  constexpr double kTan3PiOver8 = 2.41421356237309504880;
  constexpr double kMoreBits = 6.123233995736765886130e-17;  // π/2 − double(π/2)
  const bool steep = opposite > kTan3PiOver8 * adjacent;
  const bool middle = opposite > 0.66 * adjacent;
  const double difference = opposite - adjacent;
  const double sum = opposite + adjacent;
  const double numerator = steep ? adjacent : (middle ? difference : opposite);
  const double denominator = steep ? opposite : (middle ? sum : adjacent);
  const double quotient = numerator / denominator;
  const double t = denominator > 0.0 ? quotient : 0.0;
  const double z = t * t;
  const double p = (((-8.750608600031904122785e-01 * z - 1.615753718733365076637e+01) * z -
                     7.500855792314704667340e+01) *
                        z -
                    1.228866684490136173410e+02) *
                       z -
                   6.485021904942025371773e+01;
  const double q = ((((z + 2.485846490142306297962e+01) * z + 1.650270098316988542046e+02) * z +
                     4.328810604912902668951e+02) *
                        z +
                    4.853903996359136964868e+02) *
                       z +
                   1.945506571482613964425e+02;
  const double reduced = t * (z * p / q) + t;
  const double from_right = (std::numbers::pi / 2 - reduced) + kMoreBits;
  const double from_diagonal = (std::numbers::pi / 4 + reduced) + 0.5 * kMoreBits;
  const double radians = steep ? from_right : (middle ? from_diagonal : reduced);
  return radians * (180.0 / std::numbers::pi);
}
// θ = 90° − angle(ray, wire axis), the acute angle, in [0°, 90°]  (SENSOR-SPEC §7, eq 7.11)
[[nodiscard]] double wire_incidence_deg(const Eigen::Vector3d& ray_dir,
                                        const Eigen::Vector3d& wire_axis);
// θ = angle between −ray and the surface normal in [0°, 90°]; either orientation of the normal
// gives the same angle: atan2(|d × n|, |d · n|)  (SENSOR-SPEC §7 pinned per surface). By
// components, inline, for loops over arrays of hits.
[[nodiscard]] inline double surface_incidence_deg(double dx, double dy, double dz, double nx,
                                                  double ny, double nz) {
  const double cx = dy * nz - dz * ny;
  const double cy = dz * nx - dx * nz;
  const double cz = dx * ny - dy * nx;
  const double sine = std::sqrt((cx * cx + cy * cy) + cz * cz);
  const double cosine = std::abs((dx * nx + dy * ny) + dz * nz);
  return acute_angle_deg(sine, cosine);
}
[[nodiscard]] double surface_incidence_deg(const Eigen::Vector3d& ray_dir,
                                           const Eigen::Vector3d& normal);

}  // namespace owsim
