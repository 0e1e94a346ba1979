#include "geometry/utm.hpp"

#include <GeographicLib/MGRS.hpp>
#include <GeographicLib/UTMUPS.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr std::string_view kUtmBands = "CDEFGHJKLMNPQRSTUVWX";  // 8° bands from 80°S; X to 84°N
constexpr double kBandToleranceDeg = 0.01;

Error utm_text_error(std::string_view text, std::string_view problem) {
  return input_error("UTM position \"" + std::string(text) + "\"", problem);
}

std::vector<std::string_view> split_whitespace(std::string_view text) {
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    const std::size_t start = pos;
    while (pos < text.size() && !std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    if (pos > start) tokens.push_back(text.substr(start, pos - start));
  }
  return tokens;
}

bool parse_metres(std::string_view token, double& value) {
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

// The zone designator: GeographicLib's zone + hemisphere ("32n", "38south", "s"), else an MGRS
// grid zone designator (zone + latitude band, "32U", or a UPS band "Z"). Returns the band letter
// (upper case) when one was given, 0 otherwise.
char decode_zone(std::string_view text, std::string_view token, int& zone, bool& northp) {
  const std::string designator(token);
  try {
    GeographicLib::UTMUPS::DecodeZone(designator, zone, northp);
    if (zone == GeographicLib::UTMUPS::INVALID) throw utm_text_error(text, "invalid zone");
    return 0;
  } catch (const GeographicLib::GeographicErr&) {
    // not zone + hemisphere: try zone + latitude band below
  }
  const bool gzd_shape =
      std::isalpha(static_cast<unsigned char>(designator.back())) && designator.size() <= 3 &&
      std::all_of(designator.begin(), designator.end() - 1,
                  [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
  if (!gzd_shape) {
    throw utm_text_error(text, "zone \"" + designator +
                                   "\" is not a zone number with a hemisphere (n/s) or a "
                                   "latitude band letter");
  }
  try {
    double x = 0, y = 0;
    int precision = 0;
    GeographicLib::MGRS::Reverse(designator, zone, northp, x, y, precision);
  } catch (const GeographicLib::GeographicErr& error) {
    throw utm_text_error(text, error.what());
  }
  return static_cast<char>(std::toupper(static_cast<unsigned char>(designator.back())));
}

void check_band(std::string_view text, char band, double lat_deg) {
  const std::size_t index = kUtmBands.find(band);
  if (index == std::string_view::npos) return;  // a UPS band: the hemisphere says it all
  const double south_deg = -80.0 + 8.0 * static_cast<double>(index);
  const double north_deg = band == 'X' ? 84.0 : south_deg + 8.0;
  if (lat_deg < south_deg - kBandToleranceDeg || lat_deg > north_deg + kBandToleranceDeg) {
    char problem[160];
    std::snprintf(problem, sizeof problem,
                  "latitude band %c spans %g° to %g° but the point lies at %.4f°", band, south_deg,
                  north_deg, lat_deg);
    throw utm_text_error(text, problem);
  }
}

}  // namespace

UtmPoint utm_from_geodetic(double lat_deg, double lon_deg) {
  validate_geodetic({lat_deg, lon_deg, 0.0}, "UTM conversion");
  UtmPoint point;
  try {
    GeographicLib::UTMUPS::Forward(lat_deg, lon_deg, point.zone, point.northp, point.easting_m,
                                   point.northing_m);
  } catch (const GeographicLib::GeographicErr& error) {
    throw input_error("UTM conversion", error.what());
  }
  return point;
}

UtmGrid utm_grid_of(const Geodetic& point) {
  const UtmPoint standard = utm_from_geodetic(point.lat_deg, point.lon_deg);
  return {standard.zone, standard.northp};
}

Eigen::Vector2d grid_from_geodetic(const UtmGrid& grid, double lat_deg, double lon_deg) {
  int zone = 0;
  bool northp = true;
  Eigen::Vector2d en;
  try {
    GeographicLib::UTMUPS::Forward(lat_deg, lon_deg, zone, northp, en.x(), en.y(), grid.zone);
  } catch (const GeographicLib::GeographicErr& error) {
    throw Error(error.what());
  }
  if (northp != grid.northp) {
    en.y() += (grid.northp ? -1.0 : 1.0) * GeographicLib::UTMUPS::UTMShift();
  }
  return en;
}

Geodetic geodetic_from_utm(const UtmPoint& point, double h_m) {
  Geodetic geodetic{0.0, 0.0, h_m};
  try {
    GeographicLib::UTMUPS::Reverse(point.zone, point.northp, point.easting_m, point.northing_m,
                                   geodetic.lat_deg, geodetic.lon_deg);
  } catch (const GeographicLib::GeographicErr& error) {
    throw input_error("UTM position " + format_utm(point), error.what());
  }
  return geodetic;
}

UtmPoint parse_utm(std::string_view text) {
  const std::vector<std::string_view> tokens = split_whitespace(text);
  if (tokens.size() != 3) {
    throw utm_text_error(text, "expected \"ZONE EASTING NORTHING\", e.g. \"32U 634000 5394000\"");
  }
  UtmPoint point;
  const char band = decode_zone(text, tokens[0], point.zone, point.northp);
  if (!parse_metres(tokens[1], point.easting_m)) {
    throw utm_text_error(text, "easting \"" + std::string(tokens[1]) + "\" is not a number");
  }
  if (!parse_metres(tokens[2], point.northing_m)) {
    throw utm_text_error(text, "northing \"" + std::string(tokens[2]) + "\" is not a number");
  }
  double lat_deg = 0, lon_deg = 0;
  try {
    GeographicLib::UTMUPS::Reverse(point.zone, point.northp, point.easting_m, point.northing_m,
                                   lat_deg, lon_deg);
  } catch (const GeographicLib::GeographicErr& error) {
    throw utm_text_error(text, error.what());
  }
  if (band != 0) check_band(text, band, lat_deg);
  return point;
}

std::string format_utm(const UtmPoint& point) {
  std::string zone;
  try {
    zone = GeographicLib::UTMUPS::EncodeZone(point.zone, point.northp);
  } catch (const GeographicLib::GeographicErr&) {
    zone = "zone" + std::to_string(point.zone) + (point.northp ? "n" : "s");
  }
  std::array<char, 96> numbers{};
  std::snprintf(numbers.data(), numbers.size(), " %.3f %.3f", point.easting_m, point.northing_m);
  return zone + numbers.data();
}

}  // namespace owsim
