// Protects the sun's position for a scenario's `sun` (io/scenario/solar_position.hpp, SENSOR-SPEC
// §11 sunlight): the apparent elevation and north-based azimuth agree to 0.03° with a second,
// independent source — astral (Debian's python3-astral, NOAA's solar-position algorithm with its
// own refraction model) — over summer and winter, morning and evening, both hemispheres, the
// midnight sun, a low sun whose refraction alone is 0.3°, and night; ISO 8601 UTC times parse
// exactly and every malformed one is refused with the text named; given angles wrap into [0, 360).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/scenario/solar_position.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

using test::python_number;
using test::run_python;

struct Place {
  const char* time_utc;
  double lat_deg;
  double lon_deg;
  const char* what;
};

// Elevations from −64° to 63° (astral's, in the comments).
const std::vector<Place> kPlaces = {
    {"2026-06-21T10:30:00Z", 48.6881, 10.8447, "examples' origin, summer midday (63.0°)"},
    {"2026-06-21T18:00:00Z", 48.6881, 10.8447, "examples' origin, summer evening (11.0°)"},
    {"2026-12-21T07:45:00Z", 48.6881, 10.8447, "examples' origin, winter morning (4.2°)"},
    {"2026-12-21T15:00:00Z", 48.6881, 10.8447, "examples' origin, winter evening (2.4°)"},
    {"2026-12-21T23:00:00Z", 48.6881, 10.8447, "examples' origin, winter night (−64.6°)"},
    {"2026-06-21T22:30:00Z", -33.8688, 151.2093, "Sydney, winter morning (14.5°)"},
    {"2026-12-21T07:30:00Z", -33.8688, 151.2093, "Sydney, summer evening (17.4°)"},
    {"2026-03-20T15:00:00Z", 39.7392, -104.9903, "Denver, equinox morning (21.5°)"},
    {"2025-09-22T21:30:00Z", -34.6037, -58.3816, "Buenos Aires, equinox evening (3.7°)"},
    {"2026-06-21T23:00:00Z", 69.6492, 18.9553, "Tromsø, midnight sun due north (3.3°)"},
    {"2024-02-29T00:00:00.5Z", -77.85, 166.67, "McMurdo, leap day, fractional second (19.5°)"},
    {"2026-01-15T14:20:00Z", 1.3521, 103.8198, "Singapore, night (−43.2°)"},
};

// astral's (elevation, azimuth) for every place: astral ≥ 2 (astral.sun with an Observer) or
// Debian 12's astral 1.6 (Astral.solar_elevation / solar_azimuth, its Julian-day bug mended);
// both refract the elevation (NOAA's model) and count the azimuth clockwise from north.
std::vector<SunPosition> astral_positions(const std::vector<Place>& places) {
  std::string script = R"(import datetime
try:
    from astral import Observer
    from astral.sun import azimuth, elevation
    def sun(t, lat, lon):
        o = Observer(latitude=lat, longitude=lon)
        return elevation(o, t), azimuth(o, t)
except ImportError:
    import astral
    a = astral.Astral()
    # astral 1.x counts the time of day twice (its _julianday holds it, then solar_elevation
    # adds it again: the sun of up to a day later, 0.4° off near an equinox; fixed in astral 2):
    # hand it the day's Julian day at 0 h, as NOAA's algorithm it follows does.
    julian_day = a._julianday
    a._julianday = lambda t, timezone=None: julian_day(t.date())
    def sun(t, lat, lon):
        return a.solar_elevation(t, lat, lon), a.solar_azimuth(t, lat, lon)
places = [
)";
  for (const Place& place : places) {
    script += "    ('" + std::string(place.time_utc) + "', " + python_number(place.lat_deg) + ", " +
              python_number(place.lon_deg) + "),\n";
  }
  script += R"(]
for text, lat, lon in places:
    t = datetime.datetime.fromisoformat(text.replace('Z', '+00:00'))
    el, az = sun(t, lat, lon)
    print(repr(el), repr(az))
)";
  std::istringstream printed(run_python(script));
  std::vector<SunPosition> positions;
  SunPosition sun;
  while (printed >> sun.elevation_deg >> sun.azimuth_deg) positions.push_back(sun);
  return positions;
}

// |a − b| on the circle, degrees.
double azimuth_difference_deg(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

// Issue 44 asks for 0.1°; the two agree to 0.01° (NOAA's series against VSOP87, refraction
// models 0.003° apart above 2°), so a tenth of that margin is held.
constexpr double kAgreementDeg = 0.03;

TEST(SolarPosition, AgreesWithAstral) {
  const std::vector<SunPosition> astral = astral_positions(kPlaces);
  ASSERT_EQ(astral.size(), kPlaces.size());
  for (std::size_t i = 0; i < kPlaces.size(); ++i) {
    const Place& place = kPlaces[i];
    SCOPED_TRACE(place.what);
    const SunPosition sun =
        solar_position(parse_utc_time(place.time_utc), place.lat_deg, place.lon_deg);
    EXPECT_TRUE(sun.given);
    EXPECT_NEAR(sun.elevation_deg, astral[i].elevation_deg, kAgreementDeg);
    EXPECT_LT(azimuth_difference_deg(sun.azimuth_deg, astral[i].azimuth_deg), kAgreementDeg)
        << sun.azimuth_deg << " vs astral's " << astral[i].azimuth_deg;
    EXPECT_GE(sun.azimuth_deg, 0.0);
    EXPECT_LT(sun.azimuth_deg, 360.0);
  }
}

TEST(SolarPosition, TheMiddayAndMidnightSunsStandDueSouthAndNorth) {
  // The sun crosses the meridian of the examples' origin (10.8447° E: 43.379 min before 12:00)
  // on 2026-06-21 at 11:18:26 UTC (the equation of time is −1.818 min), due south at
  // 90° − 48.6881° + δ (δ = 23.4381°) plus 0.008° of refraction.
  const SunPosition noon = solar_position(parse_utc_time("2026-06-21T11:18:26Z"), 48.6881, 10.8447);
  EXPECT_NEAR(noon.azimuth_deg, 180.0, 0.02);
  EXPECT_NEAR(noon.elevation_deg, 90.0 - 48.6881 + 23.4381 + 0.008, 0.01);
  // Twelve hours later it is due north (the azimuth wraps through 0/360; the equation of time has
  // moved 6 s, 0.025° of azimuth), as far below the horizon: no refraction there.
  const SunPosition midnight =
      solar_position(parse_utc_time("2026-06-21T23:18:26Z"), 48.6881, 10.8447);
  EXPECT_LT(azimuth_difference_deg(midnight.azimuth_deg, 0.0), 0.04);
  EXPECT_NEAR(midnight.elevation_deg, -(90.0 - 48.6881 - 23.4381), 0.01);
}

TEST(SolarPosition, UtcTimesParseExactly) {
  const UtcTime t = parse_utc_time("2026-06-21T10:30:07Z");
  EXPECT_EQ(t.year, 2026);
  EXPECT_EQ(t.month, 6);
  EXPECT_EQ(t.day, 21);
  EXPECT_EQ(t.hour, 10);
  EXPECT_EQ(t.minute, 30);
  EXPECT_EQ(t.second, 7.0);
  EXPECT_EQ(parse_utc_time("2026-06-21T10:30:07.25Z").second, 7.25);
  EXPECT_EQ(parse_utc_time("2026-06-21t10:30:07z").minute, 30);
  EXPECT_EQ(parse_utc_time("2026-06-21T10:30:07+00:00").hour, 10);
  EXPECT_EQ(parse_utc_time("2024-02-29T00:00:00Z").day, 29);  // a leap year
  EXPECT_EQ(parse_utc_time("2000-02-29T00:00:00Z").day, 29);  // divisible by 400
  EXPECT_EQ(parse_utc_time("2026-12-31T23:59:59Z").second, 59.0);
  EXPECT_EQ(parse_utc_time("1900-01-01T00:00:00Z").year, 1900);  // the range's ends
  EXPECT_EQ(parse_utc_time("2100-12-31T23:59:59Z").year, 2100);
}

std::string solar_error_of(const std::string& text) {
  try {
    (void)parse_utc_time(text);
  } catch (const Error& error) {
    return error.what();
  }
  return "accepted";
}

TEST(SolarPosition, MalformedTimesAreRefusedWithTheText) {
  const std::string expected = "expected an ISO 8601 UTC time like 2026-06-21T10:30:00Z, got '";
  for (const std::string text :
       {"", "yesterday", "2026-06-21", "2026-06-21T10:30:00", "2026-06-21 10:30:00Z",
        "2026-06-21T10:30Z", "2026-6-21T10:30:00Z", "2026-06-21T10:30:00.Z",
        "2026-06-21T10:30:00Zjunk", "2026-06-21T10:30:00 Z", "+2026-06-21T10:30:00Z",
        "2026-06-21T10:30:00+0000"}) {
    EXPECT_EQ(solar_error_of(text), expected + text + "'") << text;
  }
  EXPECT_EQ(solar_error_of("2026-06-21T10:30:00+02:00"),
            "must be a UTC time (ending in Z), got the offset +02:00 in "
            "'2026-06-21T10:30:00+02:00'");
  EXPECT_EQ(solar_error_of("1899-12-31T23:59:59Z"),
            "the year must be in 1900..2100, got '1899-12-31T23:59:59Z'");
  EXPECT_EQ(solar_error_of("2101-01-01T00:00:00Z"),
            "the year must be in 1900..2100, got '2101-01-01T00:00:00Z'");
  EXPECT_EQ(solar_error_of("2026-13-01T00:00:00Z"), "no month 13 in '2026-13-01T00:00:00Z'");
  EXPECT_EQ(solar_error_of("2026-02-29T00:00:00Z"), "no day 29 in that month: '2026-02-29T00:00:00Z'");
  EXPECT_EQ(solar_error_of("2100-02-29T00:00:00Z"), "no day 29 in that month: '2100-02-29T00:00:00Z'");
  EXPECT_EQ(solar_error_of("2026-04-31T00:00:00Z"), "no day 31 in that month: '2026-04-31T00:00:00Z'");
  EXPECT_EQ(solar_error_of("2026-04-00T00:00:00Z"), "no day 0 in that month: '2026-04-00T00:00:00Z'");
  for (const std::string text :
       {"2026-06-21T24:00:00Z", "2026-06-21T10:60:00Z", "2026-06-21T10:30:60Z"}) {
    EXPECT_EQ(solar_error_of(text), "not a time of day (00:00:00 to 23:59:59): '" + text + "'");
  }
}

TEST(SolarPosition, GivenAnglesWrapTheAzimuthIntoOneTurn) {
  const SunPosition sun = sun_at_angles(45.0, -90.0);
  EXPECT_TRUE(sun.given);
  EXPECT_EQ(sun.elevation_deg, 45.0);
  EXPECT_EQ(sun.azimuth_deg, 270.0);
  EXPECT_EQ(sun_at_angles(10.0, 720.5).azimuth_deg, 0.5);
  EXPECT_EQ(sun_at_angles(10.0, 360.0).azimuth_deg, 0.0);
  EXPECT_EQ(sun_at_angles(10.0, -1e-20).azimuth_deg, 0.0);  // 360 − 1e-20 rounds to 360
  EXPECT_EQ(sun_at_angles(10.0, 135.0).azimuth_deg, 135.0);
  EXPECT_EQ(sun_at_angles(10.0, -3600.0 - 45.0).azimuth_deg, 315.0);
}

}  // namespace
}  // namespace owsim
