#pragma once
// The sun's position for the scenario's `sun` (INTERFACE.md "Receiver noise and sunlight",
// SENSOR-SPEC §11 sunlight): given as angles, or as a UTC time turned into the sun's direction at
// the scenario's origin with libnova (Debian's libnova-dev).
// - libnova gives the Julian day, the sun's geometric position (VSOP87 in FK5: the ecliptic and
//   equinox of J2000.0), the nutation, the apparent sidereal time and the horizontal transform.
//   Its own apparent place (ln_get_solar_equ_coords) is not used: libnova 0.16 leaves it at
//   J2000.0's equinox (50″ a year behind: 0.37° in 2026) with a 360-fold too small aberration.
//   owsim precesses the ecliptic position to the date (Meeus eq. 21.7), adds the nutation in
//   longitude and the aberration (−20.4898″ / R, eq. 25.10), and turns it into right ascension
//   and declination at the true obliquity (eq. 13.3, 13.4).
// - The elevation is the apparent one, as the sunlight arrives: the true altitude h lifted by
//   atmospheric refraction, h₀ = h + R(h₀) with R Bennett's formula as libnova gives it (Meeus
//   eq. 16.3, 1010 hPa, 10 °C: 0.48° at h = 0, 0.16° at 5°, 1′ at 45°), solved by fixed-point
//   iteration. Bennett's formula holds down to h₀ = −1°; a sun below that (true altitude < −1.83°)
//   keeps its true altitude: it is night either way (SENSOR-SPEC §11: b = 0 below the horizon).
// - Topocentric = geocentric: the sun's parallax (8.8″ < 0.003°) is left out; so is ΔT (UT is
//   used for TT: 0.001° of solar longitude today).
// - The azimuth is clockwise from north; libnova's counts from south and is turned by 180°.
// tests/test_solar_position.cpp holds the result to astral's (NOAA's algorithm) within 0.03°.
#include <string_view>

#include "sensor/receiver_noise.hpp"

namespace owsim {

// A UTC instant as a calendar date and time of day.
struct UtcTime {
  int year = 2000;
  int month = 1;        // 1..12
  int day = 1;          // 1..31, within the month
  int hour = 0;         // 0..23
  int minute = 0;       // 0..59
  double second = 0.0;  // [0, 60)
};

// ISO 8601 / RFC 3339 in UTC: "YYYY-MM-DDTHH:MM:SS" with optional fractional seconds, ending in
// "Z" (or "+00:00"); years 1900..2100. Throws owsim::Error with the problem (no key: the caller
// names it), e.g. "expected an ISO 8601 UTC time like 2026-06-21T10:30:00Z, got '…'".
[[nodiscard]] UtcTime parse_utc_time(std::string_view text);

// The sun seen at (lat_deg, lon_deg, east positive) at `time`: given, apparent elevation,
// azimuth in [0, 360).
[[nodiscard]] SunPosition solar_position(const UtcTime& time, double lat_deg, double lon_deg);

// A sun given by its angles (not checked: validate(ReceiverParams) does), the azimuth wrapped
// into [0, 360).
[[nodiscard]] SunPosition sun_at_angles(double elevation_deg, double azimuth_deg);

}  // namespace owsim
