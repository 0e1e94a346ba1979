#pragma once
// OGC WKT (version 1, OGC 01-009 "Coordinate Transformation Services" §7, the dialect LAS 1.4
// requires for its LASF_Projection record 2112) of the WGS-84 UTM and UPS grids, so a point file
// in easting/northing carries its coordinate reference system.
//
// UTM zone Z (1..60) north is EPSG:326ZZ, south EPSG:327ZZ: Transverse Mercator, latitude of
// origin 0°, central meridian 6°·Z − 183°, scale 0.9996, false easting 500 km, false northing 0
// (north) or 10,000 km (south). UPS (zone 0, geometry/utm.hpp) north is EPSG:5041, south
// EPSG:5042: Polar Stereographic at ±90°, scale 0.994, false easting and northing 2,000 km. The
// text is the one GDAL writes for those codes (AUTHORITY nodes included) and names the CRS like
// the EPSG registry ("WGS 84 / UTM zone 32N"); pyproj parses it back to the same EPSG code. It is
// a horizontal CRS: heights stored with it are WGS-84 ellipsoidal heights, which WKT 1 cannot
// name. Numbers are written in the C locale.
#include <string>

namespace owsim {

// The EPSG code of a WGS-84 UTM/UPS grid: 32600 + zone (north), 32700 + zone (south), 5041 (UPS
// north), 5042 (UPS south). Throws owsim::Error unless zone is 0..60.
[[nodiscard]] int utm_epsg_code(int zone, bool northp);
// "WGS 84 / UTM zone 32N", "WGS 84 / UTM zone 33S", "WGS 84 / UPS North (E,N)". Throws owsim::Error
// unless zone is 0..60.
[[nodiscard]] std::string utm_crs_name(int zone, bool northp);
// The OGC WKT 1 PROJCS of that grid, one line, no terminating null (the LAS writer adds it).
// Throws owsim::Error unless zone is 0..60.
[[nodiscard]] std::string utm_wkt(int zone, bool northp);

}  // namespace owsim
