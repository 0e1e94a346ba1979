#pragma once
// UTM/UPS grid coordinates on WGS-84, for positions a user gives or reads (SENSOR-SPEC §4,
// "Decision (world frame)": the simulation itself runs in the local ENU frame, never in UTM).
//
// Wraps GeographicLib::UTMUPS (Karney's Krüger series transverse Mercator, accurate to ~5 nm).
// The standard zone is GeographicLib's: the 6° zones with the Norway (32V widened to 3°–12°E)
// and Svalbard (31X, 33X, 35X, 37X) exceptions, and UPS (zone 0) north of 84°N and south of
// 80°S. Valid ranges are GeographicLib's: UTM eastings 0–1000 km, northings 0–9600 km (north)
// or 900–10000 km (south); UPS 1200–2800 km (north) or 700–3300 km (south).
#include <Eigen/Core>
#include <string>
#include <string_view>

#include "geometry/geodetic_frame.hpp"

namespace owsim {

struct UtmPoint {
  int zone = 0;        // 1..60 for UTM; 0 for UPS (polar)
  bool northp = true;  // hemisphere: true north, false south
  double easting_m = 0;
  double northing_m = 0;
};

// Geodetic → UTM/UPS in the standard zone (GeographicLib UTMUPS::Forward, STANDARD zone).
// Throws owsim::Error if lat is outside [−90°, 90°] or lon outside [−540°, 540°).
[[nodiscard]] UtmPoint utm_from_geodetic(double lat_deg, double lon_deg);
// UTM/UPS → geodetic at height h_m (GeographicLib UTMUPS::Reverse); lon in [−180°, 180°].
// Throws owsim::Error if the zone, easting or northing is out of range.
[[nodiscard]] Geodetic geodetic_from_utm(const UtmPoint& point, double h_m);

// A grid a whole file stays in (a LAS file's, from its origin), whatever zone a point falls in.
struct UtmGrid {
  int zone = 0;        // 1..60 UTM, 0 UPS
  bool northp = true;  // hemisphere
  friend bool operator==(const UtmGrid&, const UtmGrid&) = default;
};

// The grid of a point's standard zone (utm_from_geodetic): a file's grid from its origin.
[[nodiscard]] UtmGrid utm_grid_of(const Geodetic& point);

// Geodetic → (easting, northing) in `grid`, the zone forced (GeographicLib UTMUPS::Forward with
// setzone), one northing across the equator: a point of the other hemisphere is shifted by
// UTMUPS::UTMShift (10,000 km). Throws owsim::Error with GeographicLib's reason if the point
// lies outside the grid's valid range.
[[nodiscard]] Eigen::Vector2d grid_from_geodetic(const UtmGrid& grid, double lat_deg,
                                                 double lon_deg);

// Parses "ZONE EASTING NORTHING", whitespace separated, e.g. "32U 634000 5394000":
//   - ZONE is a zone number 1..60 followed by a hemisphere, n/s or north/south in any case
//     (GeographicLib UTMUPS::DecodeZone: "38s" is the southern hemisphere, not band S), or
//     followed by an MGRS latitude band letter C..X other than N and S (GeographicLib
//     MGRS); the band must agree with the point's latitude within 0.01°. UPS is "n"/"s" alone,
//     or the band letters A, B (south), Y, Z (north).
// Throws owsim::Error naming the whole text on anything else.
[[nodiscard]] UtmPoint parse_utm(std::string_view text);
// "32n 634000.000 5394000.000": GeographicLib's zone notation (lower-case n/s hemisphere, which
// parse_utm reads back), easting and northing to the millimetre.
[[nodiscard]] std::string format_utm(const UtmPoint& point);

}  // namespace owsim
