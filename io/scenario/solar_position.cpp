#include "io/scenario/solar_position.hpp"

#include <libnova/julian_day.h>
#include <libnova/nutation.h>
#include <libnova/refraction.h>
#include <libnova/sidereal_time.h>
#include <libnova/solar.h>
#include <libnova/transform.h>

#include <charconv>
#include <cmath>
#include <mutex>
#include <numbers>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr double kJ2000 = 2451545.0;  // Julian day of J2000.0
constexpr double kDaysPerCentury = 36525.0;
constexpr double kArcsecond = 1.0 / 3600.0;    // degrees
constexpr double kAberrationArcsec = 20.4898;  // Meeus eq. 25.10, at 1 AU
// Gregorian dates (libnova counts those before 1582 in the Julian calendar) where UT stands for TT
// to under 2 minutes (ΔT) and the precession polynomials hold to arcseconds.
constexpr int kFirstYear = 1900;
constexpr int kLastYear = 2100;
constexpr double kPressureHpa = 1010.0;  // refraction's standard atmosphere (Meeus ch. 16)
constexpr double kTemperatureC = 10.0;
constexpr double kLowestApparentDeg = -1.0;       // Bennett's formula holds above
constexpr double kRefractionToleranceDeg = 1e-9;  // the fixed point's last step (|dR/dh₀| < 0.3)

[[noreturn]] void unparseable(std::string_view text) {
  throw Error("expected an ISO 8601 UTC time like 2026-06-21T10:30:00Z, got '" + std::string(text) +
              "'");
}

// The unsigned decimal of exactly `digits` digits at text[at], or -1.
int digits_at(std::string_view text, std::size_t at, std::size_t digits) {
  if (at + digits > text.size()) return -1;
  int value = 0;
  for (std::size_t i = at; i < at + digits; ++i) {
    if (text[i] < '0' || text[i] > '9') return -1;
    value = value * 10 + (text[i] - '0');
  }
  return value;
}

// The fractional seconds ".ddd" at text[at] (0 when there are none); `at` moves past them.
double fraction_at(std::string_view text, std::size_t& at) {
  if (at >= text.size() || text[at] != '.') return 0.0;
  const std::size_t first = at + 1;
  std::size_t end = first;
  while (end < text.size() && text[end] >= '0' && text[end] <= '9') ++end;
  if (end == first) unparseable(text);
  at = end;
  const std::string digits = "0." + std::string(text.substr(first, end - first));
  double fraction = 0.0;
  std::from_chars(digits.data(), digits.data() + digits.size(), fraction);
  return fraction;
}

// The zone must say UTC: "Z" (or "z", "+00:00"); another offset is refused by name.
void check_utc_zone(std::string_view text, std::string_view zone) {
  if (zone == "Z" || zone == "z" || zone == "+00:00") return;
  if (zone.size() == 6 && (zone[0] == '+' || zone[0] == '-') && zone[3] == ':' &&
      digits_at(zone, 1, 2) >= 0 && digits_at(zone, 4, 2) >= 0) {
    throw Error("must be a UTC time (ending in Z), got the offset " + std::string(zone) + " in '" +
                std::string(text) + "'");
  }
  unparseable(text);
}

bool is_leap_year(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int days_in_month(int year, int month) {
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && is_leap_year(year) ? 29 : kDays[month - 1];
}

// Ecliptic coordinates, degrees.
struct Ecliptic {
  double lon_deg;
  double lat_deg;
};

double radians(double deg) { return deg * std::numbers::pi / 180.0; }
double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

// Ecliptic coordinates referred to J2000.0 turned to the mean ecliptic and equinox of the date t
// Julian centuries later (Meeus eq. 21.7 with T = 0): libnova 0.16 leaves the sun at J2000.0's
// equinox (50″ a year behind: 0.37° in 2026) and implements no ecliptic precession.
Ecliptic precessed_from_j2000(Ecliptic j2000, double t) {
  const double eta = radians((47.0029 * t - 0.03302 * t * t + 0.000060 * t * t * t) * kArcsecond);
  const double pi_deg = 174.876384 - (869.8089 * t - 0.03536 * t * t) * kArcsecond;  // Π
  const double p_deg = (5029.0966 * t + 1.11113 * t * t - 0.000006 * t * t * t) * kArcsecond;
  const double beta = radians(j2000.lat_deg);
  const double node = radians(pi_deg - j2000.lon_deg);
  const double a = std::cos(eta) * std::cos(beta) * std::sin(node) - std::sin(eta) * std::sin(beta);
  const double b = std::cos(beta) * std::cos(node);
  const double c = std::cos(eta) * std::sin(beta) + std::sin(eta) * std::cos(beta) * std::sin(node);
  return {p_deg + pi_deg - degrees(std::atan2(a, b)), degrees(std::asin(c))};
}

// Right ascension and declination of ecliptic coordinates at obliquity ε (Meeus eq. 13.3, 13.4).
ln_equ_posn equatorial_of(Ecliptic e, double obliquity_deg) {
  const double lambda = radians(e.lon_deg);
  const double beta = radians(e.lat_deg);
  const double epsilon = radians(obliquity_deg);
  ln_equ_posn equatorial{};
  equatorial.ra = degrees(std::atan2(
      std::sin(lambda) * std::cos(epsilon) - std::tan(beta) * std::sin(epsilon), std::cos(lambda)));
  equatorial.dec = degrees(std::asin(std::sin(beta) * std::cos(epsilon) +
                                     std::cos(beta) * std::sin(epsilon) * std::sin(lambda)));
  return equatorial;
}

// The apparent altitude h₀ of a body at true altitude h: h₀ = h + R(h₀), Bennett's R taking the
// apparent altitude (libnova, Meeus eq. 16.3); h itself below Bennett's range.
double apparent_altitude_deg(double true_deg) {
  const double lowest_true =
      kLowestApparentDeg - ln_get_refraction_adj(kLowestApparentDeg, kPressureHpa, kTemperatureC);
  if (true_deg < lowest_true) return true_deg;
  double apparent = true_deg;
  for (double step = 1.0; std::abs(step) > kRefractionToleranceDeg;) {
    const double next = true_deg + ln_get_refraction_adj(apparent, kPressureHpa, kTemperatureC);
    step = next - apparent;
    apparent = next;
  }
  return apparent;
}

}  // namespace

UtcTime parse_utc_time(std::string_view text) {
  // YYYY-MM-DDTHH:MM:SS, then .fraction, then the zone
  UtcTime time;
  time.year = digits_at(text, 0, 4);
  time.month = digits_at(text, 5, 2);
  time.day = digits_at(text, 8, 2);
  time.hour = digits_at(text, 11, 2);
  time.minute = digits_at(text, 14, 2);
  const int whole_second = digits_at(text, 17, 2);
  if (text.size() < 20 || text[4] != '-' || text[7] != '-' ||
      (text[10] != 'T' && text[10] != 't') || text[13] != ':' || text[16] != ':' || time.year < 0 ||
      time.month < 0 || time.day < 0 || time.hour < 0 || time.minute < 0 || whole_second < 0) {
    unparseable(text);
  }
  std::size_t zone_at = 19;
  time.second = whole_second + fraction_at(text, zone_at);
  check_utc_zone(text, text.substr(zone_at));
  const std::string quoted = "'" + std::string(text) + "'";
  if (time.year < kFirstYear || time.year > kLastYear) {
    throw Error("the year must be in " + std::to_string(kFirstYear) + ".." +
                std::to_string(kLastYear) + ", got " + quoted);
  }
  if (time.month < 1 || time.month > 12) {
    throw Error("no month " + std::to_string(time.month) + " in " + quoted);
  }
  if (time.day < 1 || time.day > days_in_month(time.year, time.month)) {
    throw Error("no day " + std::to_string(time.day) + " in that month: " + quoted);
  }
  if (time.hour > 23 || time.minute > 59 || whole_second > 59) {
    throw Error("not a time of day (00:00:00 to 23:59:59): " + quoted);
  }
  return time;
}

SunPosition solar_position(const UtcTime& time, double lat_deg, double lon_deg) {
  ln_date date{};
  date.years = time.year;
  date.months = time.month;
  date.days = time.day;
  date.hours = time.hour;
  date.minutes = time.minute;
  date.seconds = time.second;
  ln_equ_posn equatorial{};
  ln_hrz_posn horizontal{};
  ln_lnlat_posn observer{};
  observer.lng = lon_deg;
  observer.lat = lat_deg;
  {
    // libnova caches its last Earth position and nutation in static variables.
    static std::mutex libnova;
    const std::lock_guard<std::mutex> lock(libnova);
    const double julian_day = ln_get_julian_day(&date);
    ln_helio_posn geometric{};  // VSOP87, FK5: the mean ecliptic and equinox of J2000.0
    ln_get_solar_geom_coords(julian_day, &geometric);
    ln_nutation nutation{};  // degrees; `ecliptic` is the mean obliquity
    ln_get_nutation(julian_day, &nutation);
    Ecliptic sun =
        precessed_from_j2000({geometric.L, geometric.B}, (julian_day - kJ2000) / kDaysPerCentury);
    sun.lon_deg += nutation.longitude - kAberrationArcsec * kArcsecond / geometric.R;
    equatorial = equatorial_of(sun, nutation.ecliptic + nutation.obliquity);
    ln_get_hrz_from_equ_sidereal_time(&equatorial, &observer,
                                      ln_get_apparent_sidereal_time(julian_day), &horizontal);
  }
  // libnova's azimuth: 0 = south, 90 = west; north-based: add 180°.
  return sun_at_angles(apparent_altitude_deg(horizontal.alt), horizontal.az + 180.0);
}

SunPosition sun_at_angles(double elevation_deg, double azimuth_deg) {
  SunPosition sun;
  sun.given = true;
  sun.elevation_deg = elevation_deg;
  double wrapped = std::fmod(azimuth_deg, 360.0);
  if (wrapped < 0.0) wrapped += 360.0;
  sun.azimuth_deg = wrapped >= 360.0 ? 0.0 : wrapped;  // a tiny negative azimuth rounds to 360
  return sun;
}

}  // namespace owsim
