// Protects the OGC WKT of the WGS-84 UTM/UPS grids that points.las carries (LAS 1.4 R15 record
// 2112): names and EPSG codes, and pyproj as the independent oracle — it parses every WKT to
// the right EPSG code, identifies it from the parameters alone, and projects a point to the
// same easting/northing as GeographicLib.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/utm.hpp"
#include "io/points/utm_wkt.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

using test::run_python;

TEST(UtmWkt, NamesAndEpsgCodes) {
  EXPECT_EQ(utm_crs_name(32, true), "WGS 84 / UTM zone 32N");
  EXPECT_EQ(utm_crs_name(1, false), "WGS 84 / UTM zone 1S");
  EXPECT_EQ(utm_crs_name(0, true), "WGS 84 / UPS North (E,N)");
  EXPECT_EQ(utm_epsg_code(32, true), 32632);
  EXPECT_EQ(utm_epsg_code(60, false), 32760);
  EXPECT_EQ(utm_epsg_code(1, true), 32601);
  EXPECT_EQ(utm_epsg_code(0, true), 5041);
  EXPECT_EQ(utm_epsg_code(0, false), 5042);
  const std::string wkt = utm_wkt(33, false);
  EXPECT_EQ(wkt.rfind(R"(PROJCS["WGS 84 / UTM zone 33S",)", 0), 0u) << wkt;
  EXPECT_NE(wkt.find(R"(PARAMETER["central_meridian",15])"), std::string::npos) << wkt;
  EXPECT_NE(wkt.find(R"(PARAMETER["false_northing",10000000])"), std::string::npos) << wkt;
  EXPECT_EQ(wkt.find('\0'), std::string::npos);
}

TEST(UtmWkt, ZonesOutOfRangeThrow) {
  EXPECT_THROW((void)utm_wkt(61, true), Error);
  EXPECT_THROW((void)utm_wkt(-1, true), Error);
  EXPECT_THROW((void)utm_epsg_code(61, false), Error);
}

TEST(UtmWkt, PyprojParsesEveryZoneToItsEpsgCodeAndProjectsLikeGeographicLib) {
  struct Case {
    int zone;
    bool northp;
    double lat_deg;
    double lon_deg;
  };
  std::vector<Case> cases;
  for (const int zone : {1, 2, 17, 31, 32, 33, 45, 59, 60}) {
    const double central_meridian = 6.0 * zone - 183.0;
    cases.push_back({zone, true, 48.3, central_meridian + 1.3});
    cases.push_back({zone, false, -33.7, central_meridian - 2.1});
  }
  cases.push_back({0, true, 87.0, 40.0});
  cases.push_back({0, false, -85.0, -120.0});

  std::ostringstream script;
  script.precision(17);
  script << "from pyproj import CRS, Transformer\n"
            "cases = [\n";
  for (const Case& c : cases) {
    script << "  (r'''" << utm_wkt(c.zone, c.northp) << "''', " << c.lat_deg << ", " << c.lon_deg
           << "),\n";
  }
  script << "]\n"
            "import re\n"
            "for wkt, lat, lon in cases:\n"
            "    crs = CRS(wkt)\n"
            "    bare_wkt = re.sub(r',AUTHORITY\\[\"EPSG\",\"\\d+\"\\]\\]$', ']', wkt)\n"
            "    assert bare_wkt != wkt and bare_wkt.endswith(']]')\n"
            "    bare = CRS(bare_wkt)\n"
            "    code = crs.to_epsg()\n"
            "    t = Transformer.from_crs('EPSG:4326', crs, always_xy=True)\n"
            "    e, n = t.transform(lon, lat)\n"
            "    print(code, bare.to_epsg(min_confidence=90), "
            "int(bare.equals(CRS.from_epsg(code))), repr(e), repr(n))\n";
  std::istringstream output(run_python(script.str(), {.with_stderr = true}));
  for (const Case& c : cases) {
    SCOPED_TRACE(utm_crs_name(c.zone, c.northp));
    int code = 0, bare_code = 0, equal = 0;
    double easting_m = 0, northing_m = 0;
    ASSERT_TRUE(output >> code >> bare_code >> equal >> easting_m >> northing_m);
    EXPECT_EQ(code, utm_epsg_code(c.zone, c.northp));
    EXPECT_EQ(bare_code, utm_epsg_code(c.zone, c.northp));  // identified by its parameters
    EXPECT_EQ(equal, 1);
    const UtmPoint expected = utm_from_geodetic(c.lat_deg, c.lon_deg);
    ASSERT_EQ(expected.zone, c.zone);
    ASSERT_EQ(expected.northp, c.northp);
    EXPECT_NEAR(easting_m, expected.easting_m, 1e-3);
    EXPECT_NEAR(northing_m, expected.northing_m, 1e-3);
  }
}

}  // namespace
}  // namespace owsim
