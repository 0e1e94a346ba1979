#pragma once
// Fog and cloud volumes (SENSOR-SPEC §10 "Media", scenario key weather.fog): uniform media of a
// given visibility filling the whole sky, a horizontal layer between two heights of the local
// frame, or an axis-aligned box in local ENU. Pure geometry: where a ray runs inside a volume.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace owsim {

enum class FogShape { sky, layer, box };

struct FogVolume {
  std::string id;
  double visibility_m = 1000.0;  // meteorological visibility V (2 % contrast)
  FogShape shape = FogShape::sky;
  double base_m = 0.0;  // layer: from u = base_m …
  double top_m = 0.0;   // … to u = top_m
  Eigen::AlignedBox3d box = Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
};

// The stretch [enter_m, exit_m] of the ray origin + t·dir (dir of unit length), t ∈ [0, t_max_m],
// that lies inside the volume (its boundary included), or nullopt when the ray misses it or only
// touches it in a point. Exact slab tests in double.
struct PathInterval {
  double enter_m = 0.0;
  double exit_m = 0.0;
};
[[nodiscard]] std::optional<PathInterval> path_interval(const FogVolume& volume,
                                                        const Eigen::Vector3d& origin,
                                                        const Eigen::Vector3d& dir, double t_max_m);

}  // namespace owsim
