#include "io/points/utm_wkt.hpp"

#include <string_view>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr int kUtmZones = 60;

void require_zone(int zone) {
  if (zone < 0 || zone > kUtmZones) {
    throw Error("UTM zone " + std::to_string(zone) + " is not 0 (UPS) or 1..60");
  }
}

// The geographic CRS every grid is built on: EPSG:4326 as GDAL writes it in WKT 1.
constexpr std::string_view kWgs84Geogcs =
    R"(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563,)"
    R"(AUTHORITY["EPSG","7030"]],AUTHORITY["EPSG","6326"]],)"
    R"(PRIMEM["Greenwich",0,AUTHORITY["EPSG","8901"]],)"
    R"(UNIT["degree",0.0174532925199433,AUTHORITY["EPSG","9122"]],AUTHORITY["EPSG","4326"]])";

constexpr std::string_view kMetre = R"(UNIT["metre",1,AUTHORITY["EPSG","9001"]])";

std::string parameter(std::string_view name, long long value) {
  return R"(PARAMETER[")" + std::string(name) + R"(",)" + std::to_string(value) + "]";
}

}  // namespace

int utm_epsg_code(int zone, bool northp) {
  require_zone(zone);
  if (zone == 0) return northp ? 5041 : 5042;
  return (northp ? 32600 : 32700) + zone;
}

std::string utm_crs_name(int zone, bool northp) {
  require_zone(zone);
  if (zone == 0) return northp ? "WGS 84 / UPS North (E,N)" : "WGS 84 / UPS South (E,N)";
  return "WGS 84 / UTM zone " + std::to_string(zone) + (northp ? "N" : "S");
}

std::string utm_wkt(int zone, bool northp) {
  std::string wkt = R"(PROJCS[")" + utm_crs_name(zone, northp) + R"(",)";
  wkt += kWgs84Geogcs;
  if (zone == 0) {
    wkt += R"(,PROJECTION["Polar_Stereographic"],)";
    wkt += parameter("latitude_of_origin", northp ? 90 : -90) + ",";
    wkt += parameter("central_meridian", 0) + ",";
    wkt += R"(PARAMETER["scale_factor",0.994],)";
    wkt += parameter("false_easting", 2000000) + ",";
    wkt += parameter("false_northing", 2000000) + ",";
    wkt += kMetre;
  } else {
    wkt += R"(,PROJECTION["Transverse_Mercator"],)";
    wkt += parameter("latitude_of_origin", 0) + ",";
    wkt += parameter("central_meridian", 6 * zone - 183) + ",";
    wkt += R"(PARAMETER["scale_factor",0.9996],)";
    wkt += parameter("false_easting", 500000) + ",";
    wkt += parameter("false_northing", northp ? 0 : 10000000) + ",";
    wkt += kMetre;
    wkt += R"(,AXIS["Easting",EAST],AXIS["Northing",NORTH])";
  }
  wkt += R"(,AUTHORITY["EPSG",")" + std::to_string(utm_epsg_code(zone, northp)) + R"("]])";
  return wkt;
}

}  // namespace owsim
