#include "geometry/geodetic_frame.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {

void validate_geodetic(const Geodetic& point, std::string_view where) {
  if (!(point.lat_deg >= -90.0 && point.lat_deg <= 90.0)) {
    throw input_error(where,
                      "latitude " + number_text(point.lat_deg, 10) + "° is outside [-90°, 90°]");
  }
  if (!(point.lon_deg >= -540.0 && point.lon_deg < 540.0)) {
    throw input_error(where,
                      "longitude " + number_text(point.lon_deg, 10) + "° is outside [-540°, 540°)");
  }
  if (!std::isfinite(point.h_m)) {
    throw input_error(where, "height " + number_text(point.h_m, 10) + " m is not finite");
  }
}

LocalFrame::LocalFrame(const Geodetic& origin) : origin_(origin) {
  validate_geodetic(origin, "local frame origin");
  cartesian_.Reset(origin.lat_deg, origin.lon_deg, origin.h_m);
}

Eigen::Vector3d LocalFrame::enu_from_geodetic(const Geodetic& point) const {
  validate_geodetic(point, "geodetic position");
  Eigen::Vector3d enu;
  cartesian_.Forward(point.lat_deg, point.lon_deg, point.h_m, enu.x(), enu.y(), enu.z());
  return enu;
}

Geodetic LocalFrame::geodetic_from_enu(const Eigen::Vector3d& enu_m) const {
  Geodetic point;
  cartesian_.Reverse(enu_m.x(), enu_m.y(), enu_m.z(), point.lat_deg, point.lon_deg, point.h_m);
  return point;
}

Eigen::Matrix3d LocalFrame::enu_rotation_at(const Eigen::Vector3d& position_enu_m) const {
  std::vector<double> row_major(9);
  double lat_deg = 0, lon_deg = 0, h_m = 0;
  cartesian_.Reverse(position_enu_m.x(), position_enu_m.y(), position_enu_m.z(), lat_deg, lon_deg,
                     h_m, row_major);
  Eigen::Matrix3d m;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) m(row, col) = row_major[std::size_t(3 * row + col)];
  }
  return m;
}

Geodetic origin_of_frame(const Geodetic& point, const Eigen::Vector3d& enu_m) {
  validate_geodetic(point, "origin_of_frame");
  if (!enu_m.allFinite()) throw Error("origin_of_frame: the local coordinates are not finite");
  Geodetic origin = point;
  for (int step = 0; step < 8; ++step) {
    const LocalFrame frame(origin);
    const Eigen::Vector3d residual = frame.enu_from_geodetic(point) - enu_m;
    origin = frame.geodetic_from_enu(residual);
    if (residual.norm() < 1e-6) break;
  }
  return origin;
}

}  // namespace owsim
