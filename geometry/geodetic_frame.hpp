#pragma once
// The simulation's world frame: an exact local Cartesian East-North-Up frame on WGS-84 around a
// scenario origin (SENSOR-SPEC §4, "Decision (world frame)").
//
// Wraps GeographicLib::LocalCartesian (via geocentric ECEF coordinates, Karney's Geocentric
// class): x east, y north, z along the ellipsoid normal at the origin; the plane z = −h0 is
// tangent to the ellipsoid. The conversion is exact to rounding: round trips within 50 km of the
// origin agree to a few nanometres (one ulp of an ECEF coordinate is 0.9 nm); it matches an
// independent ECEF implementation (pyproj) to 1e-6 m. Valid for any point on or near the Earth; the
// origin must have latitude in [−90°, 90°], longitude in [−540°, 540°) and a finite height.
//
// LocalCartesian::Forward/Reverse are const and touch only plain member values (no mutable state,
// no caches), so one LocalFrame may be shared read-only by many threads.
#include <Eigen/Core>
#include <GeographicLib/LocalCartesian.hpp>
#include <string_view>

namespace owsim {

// A WGS-84 position: latitude and longitude in degrees, height above the ellipsoid in metres.
struct Geodetic {
  double lat_deg = 0;
  double lon_deg = 0;
  double h_m = 0;
};

// Throws owsim::Error "<where>: <problem>" unless lat ∈ [−90°, 90°], lon ∈ [−540°, 540°) and
// h is finite (the ranges GeographicLib accepts).
void validate_geodetic(const Geodetic& point, std::string_view where);

class LocalFrame {
 public:
  // Throws owsim::Error if the origin is out of range (validate_geodetic).
  explicit LocalFrame(const Geodetic& origin);

  // Geodetic → local East-North-Up metres. Throws owsim::Error if the point is out of range.
  [[nodiscard]] Eigen::Vector3d enu_from_geodetic(const Geodetic& point) const;
  // Local East-North-Up metres → geodetic; longitude in [−180°, 180°], the nearest point on the
  // ellipsoid's normal (GeographicLib's choice where several exist).
  [[nodiscard]] Geodetic geodetic_from_enu(const Eigen::Vector3d& enu_m) const;
  // The rotation taking vectors in the local-level East-North-Up axes at position_enu_m (the
  // axes an IMU's attitude refers to there) into this frame's axes: v_frame = M · v_local.
  // Identity at the origin; it turns by ~0.009° per km away from it (the plumb lines converge).
  [[nodiscard]] Eigen::Matrix3d enu_rotation_at(const Eigen::Vector3d& position_enu_m) const;

  [[nodiscard]] const Geodetic& origin() const { return origin_; }

 private:
  Geodetic origin_;
  GeographicLib::LocalCartesian cartesian_;
};

// The origin of the local frame in which `point` lies at enu_m: the inverse of
// LocalFrame::enu_from_geodetic with respect to the origin, for files that give a position both
// ways (trajectory.csv) but not the origin. Fixed-point iteration, each step moving the trial
// origin by the residual in its own frame (the frames' rotation differs by ~0.009° per km, so
// the residual shrinks ~10⁴× a step within 1 km); stops below 1 µm or after 8 steps. Throws
// owsim::Error for a point out of range or non-finite enu_m.
[[nodiscard]] Geodetic origin_of_frame(const Geodetic& point, const Eigen::Vector3d& enu_m);

}  // namespace owsim
