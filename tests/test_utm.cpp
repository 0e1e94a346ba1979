// Protects UTM/UPS input and output (SENSOR-SPEC §4 "Decision (world frame)"): GeographicLib's
// published example, pyproj as an independent oracle, the zone exceptions, and the parser's
// acceptance of zone designators and rejection of garbage.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/utm.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

using test::python_number;
using test::run_python;

TEST(Utm, GeographicLibPublishedExample) {
  // GeoConvert documentation: "33.3 44.4" → "38n 444140.54 3684706.36".
  const UtmPoint p = utm_from_geodetic(33.3, 44.4);
  EXPECT_EQ(p.zone, 38);
  EXPECT_TRUE(p.northp);
  EXPECT_NEAR(p.easting_m, 444140.54, 0.01);
  EXPECT_NEAR(p.northing_m, 3684706.36, 0.01);
  EXPECT_EQ(format_utm(p).substr(0, 4), "38n ");
}

TEST(Utm, StandardZoneExceptions) {
  EXPECT_EQ(utm_from_geodetic(48.0, 10.0).zone, 32);
  EXPECT_EQ(utm_from_geodetic(60.5, 4.0).zone, 32);  // Norway: 32V spans 3°E..12°E
  EXPECT_EQ(utm_from_geodetic(55.5, 4.0).zone, 31);  // south of 56°N no exception
  EXPECT_EQ(utm_from_geodetic(78.2, 8.0).zone, 31);  // Svalbard: 31X to 9°E
  EXPECT_EQ(utm_from_geodetic(78.2, 10.0).zone, 33);
  EXPECT_EQ(utm_from_geodetic(78.2, 22.0).zone, 35);
  EXPECT_EQ(utm_from_geodetic(78.2, 34.0).zone, 37);
  const UtmPoint north_pole = utm_from_geodetic(85.0, 0.0);
  EXPECT_EQ(north_pole.zone, 0);  // UPS
  EXPECT_TRUE(north_pole.northp);
  const UtmPoint south = utm_from_geodetic(-85.0, 0.0);
  EXPECT_EQ(south.zone, 0);
  EXPECT_FALSE(south.northp);
  EXPECT_FALSE(utm_from_geodetic(-33.9, 18.4).northp);
  EXPECT_EQ(utm_from_geodetic(-33.9, 18.4).zone, 34);
}

TEST(Utm, RoundTripToANanodegree) {
  std::mt19937_64 rng(31337);
  std::uniform_real_distribution<double> lat(-89.9, 89.9), lon(-180.0, 180.0),
      height(-100.0, 5000.0);
  for (int i = 0; i < 5000; ++i) {
    const double lat_deg = lat(rng), lon_deg = lon(rng), h_m = height(rng);
    const Geodetic back = geodetic_from_utm(utm_from_geodetic(lat_deg, lon_deg), h_m);
    EXPECT_NEAR(back.lat_deg, lat_deg, 1e-9) << lat_deg << " " << lon_deg;
    EXPECT_NEAR(back.lon_deg, lon_deg, 1e-9) << lat_deg << " " << lon_deg;
    EXPECT_EQ(back.h_m, h_m);
  }
}

TEST(Utm, AgreesWithPyproj) {
  const std::vector<std::array<double, 2>> points = {
      {48.6881, 10.8447}, {-33.9, 18.4},  {35.7, 139.7}, {-22.9, -43.2}, {40.7, -74.0},
      {64.1, -21.9},      {-45.0, 170.5}, {1.3, 103.8},  {-0.5, -78.5},  {60.5, 4.0},
      {78.2, 15.6},       {-77.8, 166.7}, {33.3, 44.4},  {19.4, -99.1}};
  std::ostringstream script;
  script << "from pyproj import Transformer\n"
            "for lat, lon, epsg in [";
  std::vector<UtmPoint> ours;
  for (const auto& [lat, lon] : points) {
    ours.push_back(utm_from_geodetic(lat, lon));
    const int epsg = (ours.back().northp ? 32600 : 32700) + ours.back().zone;
    script << "(" << python_number(lat) << ", " << python_number(lon) << ", " << epsg << "),";
  }
  script << "]:\n"
            "    t = Transformer.from_crs('EPSG:4326', 'EPSG:%d' % epsg, always_xy=True)\n"
            "    print('%.17g %.17g' % t.transform(lon, lat))\n";
  std::istringstream output(run_python(script.str()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    double easting = 0, northing = 0;
    ASSERT_TRUE(output >> easting >> northing);
    EXPECT_NEAR(ours[i].easting_m, easting, 1e-4) << points[i][0] << " " << points[i][1];
    EXPECT_NEAR(ours[i].northing_m, northing, 1e-4) << points[i][0] << " " << points[i][1];
  }
}

void expect_point(const UtmPoint& p, int zone, bool northp, double easting, double northing) {
  EXPECT_EQ(p.zone, zone);
  EXPECT_EQ(p.northp, northp);
  EXPECT_EQ(p.easting_m, easting);
  EXPECT_EQ(p.northing_m, northing);
}

TEST(Utm, ParsesZoneWithBandOrHemisphere) {
  expect_point(parse_utm("32U 634000 5394000"), 32, true, 634000, 5394000);
  expect_point(parse_utm("32u 634000 5394000"), 32, true, 634000, 5394000);
  expect_point(parse_utm("32n 634000 5394000"), 32, true, 634000, 5394000);
  expect_point(parse_utm("32N 634000 5394000"), 32, true, 634000, 5394000);
  expect_point(parse_utm("32north 634000 5394000"), 32, true, 634000, 5394000);
  expect_point(parse_utm("  32U\t634000.25   5394000.5 "), 32, true, 634000.25, 5394000.5);
  // GeographicLib's rule: "s" is the southern hemisphere, never band S.
  expect_point(parse_utm("33s 500000 6000000"), 33, false, 500000, 6000000);
  expect_point(parse_utm("33S 500000 6000000"), 33, false, 500000, 6000000);
  expect_point(parse_utm("7South 500000 6000000"), 7, false, 500000, 6000000);
  // Band letters south of the equator give the southern hemisphere: 34H is 32°S..40°S.
  expect_point(parse_utm("34H 261000 6245000"), 34, false, 261000, 6245000);
  // The stated example lies in band U (48°N..56°N).
  EXPECT_NEAR(geodetic_from_utm(parse_utm("32U 634000 5394000"), 0).lat_deg, 48.68, 0.01);
  // UPS: hemisphere alone, or a polar band letter.
  expect_point(parse_utm("n 2000000 2000000"), 0, true, 2000000, 2000000);
  expect_point(parse_utm("Z 2100000 2000000"), 0, true, 2100000, 2000000);
  expect_point(parse_utm("b 2100000 2000000"), 0, false, 2100000, 2000000);
  EXPECT_NEAR(geodetic_from_utm(parse_utm("n 2000000 2000000"), 0).lat_deg, 90.0, 1e-9);
}

void expect_parse_error(const std::string& text) {
  try {
    (void)parse_utm(text);
    ADD_FAILURE() << "no error for \"" << text << "\"";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("\"" + text + "\""), std::string::npos)
        << error.what();
  }
}

TEST(Utm, RejectsGarbageNamingTheText) {
  expect_parse_error("32X");
  expect_parse_error("abc");
  expect_parse_error("32U 634000");
  expect_parse_error("");
  expect_parse_error("32U 634000 5394000 12");
  expect_parse_error("32U 634x00 5394000");
  expect_parse_error("32U 634000 nan");
  expect_parse_error("32U 634000 5394000m");
  expect_parse_error("61n 500000 5000000");   // no zone 61
  expect_parse_error("0n 500000 5000000");    // UPS has no zone number
  expect_parse_error("32I 634000 5394000");   // I is not a band
  expect_parse_error("32UU 634000 5394000");  // a 100 km square is not a zone
  expect_parse_error("INV 500000 5000000");
  expect_parse_error("32n -5 5394000");      // easting out of range
  expect_parse_error("32n 500000 9700000");  // northing out of range
  // A band that contradicts the northing: 5394000 m is 48.7°N, not band T (40..48) or X (72..84).
  expect_parse_error("32T 634000 5394000");
  expect_parse_error("32X 634000 5394000");
  expect_parse_error("32C 634000 5394000");
}

TEST(Utm, FormatReadsBack) {
  const UtmPoint p{32, true, 634000.1234, 5394000.5};
  EXPECT_EQ(format_utm(p), "32n 634000.123 5394000.500");
  const UtmPoint back = parse_utm(format_utm(p));
  EXPECT_EQ(back.zone, 32);
  EXPECT_TRUE(back.northp);
  EXPECT_NEAR(back.easting_m, p.easting_m, 5e-4);
  EXPECT_EQ(format_utm({34, false, 261000, 6245000}), "34s 261000.000 6245000.000");
  EXPECT_EQ(format_utm({0, true, 2000000, 2000000}), "n 2000000.000 2000000.000");
}

TEST(Utm, RejectsOutOfRangeCoordinates) {
  EXPECT_THROW((void)utm_from_geodetic(91.0, 0.0), Error);
  EXPECT_THROW((void)utm_from_geodetic(0.0, 600.0), Error);
  EXPECT_THROW((void)geodetic_from_utm({32, true, -100, 5000000}, 0), Error);
  EXPECT_THROW((void)geodetic_from_utm({61, true, 500000, 5000000}, 0), Error);
}

}  // namespace
}  // namespace owsim
