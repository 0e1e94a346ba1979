// points.las read back for `owsim view` (io/report/report_points.hpp).
#include <GeographicLib/UTMUPS.hpp>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <regex>
#include <string>

#include "geometry/error.hpp"
#include "geometry/scene.hpp"
#include "io/files/input_file.hpp"
#include "io/report/report_points.hpp"

namespace owsim {
namespace {

template <typename T>
T field(const char* bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes + offset, sizeof value);  // LAS is little-endian, as is the host
  return value;
}

std::uint8_t surface_of_asprs(std::uint8_t code) {
  switch (code) {
    case 2:
      return static_cast<std::uint8_t>(SurfaceClass::ground);
    case 5:
      return static_cast<std::uint8_t>(SurfaceClass::tree);
    case 6:
      return static_cast<std::uint8_t>(SurfaceClass::building);
    case 7:
      return static_cast<std::uint8_t>(SurfaceClass::noise);
    case 14:
      return static_cast<std::uint8_t>(SurfaceClass::wire);
    case 15:
      return static_cast<std::uint8_t>(SurfaceClass::pole);
    case 18:
      return static_cast<std::uint8_t>(SurfaceClass::fog);
    default:
      return kUnknownSurface;
  }
}

struct LasGridRead {
  int zone = 0;  // 1..60 UTM, 0 UPS
  bool northp = true;
};

// The zone from the WKT's name: "WGS 84 / UTM zone 32N" or "WGS 84 / UPS North (E,N)".
std::optional<LasGridRead> grid_of_wkt(const std::string& wkt) {
  std::smatch match;
  if (std::regex_search(wkt, match, std::regex(R"(UTM zone (\d{1,2})([NS]))"))) {
    return LasGridRead{std::stoi(match[1].str()), match[2].str() == "N"};
  }
  if (std::regex_search(wkt, match, std::regex(R"(UPS (North|South))"))) {
    return LasGridRead{0, match[1].str() == "North"};
  }
  return std::nullopt;
}

}  // namespace

ReportPoints read_report_points_las(const std::filesystem::path& path,
                                    const std::optional<Geodetic>& origin) {
  const auto bad = [&](const std::string& problem) { return input_error(path.string(), problem); };
  const std::uintmax_t size = require_input_file(path, "points file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path.string(), "cannot open for reading");
  std::array<char, 375> header{};
  in.read(header.data(), header.size());
  if (!in || std::memcmp(header.data(), "LASF", 4) != 0 || header[24] != 1 || header[25] != 4) {
    throw bad("not a LAS 1.4 file");
  }
  const auto header_size = field<std::uint16_t>(header.data(), 94);
  const auto point_offset = field<std::uint32_t>(header.data(), 96);
  const auto vlr_count = field<std::uint32_t>(header.data(), 100);
  const auto format = static_cast<std::uint8_t>(header[104]);
  const auto record_bytes = field<std::uint16_t>(header.data(), 105);
  const std::array<double, 3> scale = {field<double>(header.data(), 131),
                                       field<double>(header.data(), 139),
                                       field<double>(header.data(), 147)};
  const std::array<double, 3> offset = {field<double>(header.data(), 155),
                                        field<double>(header.data(), 163),
                                        field<double>(header.data(), 171)};
  const auto count = field<std::uint64_t>(header.data(), 247);
  if ((format & 0x3F) != 6 || record_bytes < 30) {
    throw bad("point format " + std::to_string(format & 0x3F) + ", owsim view reads format 6");
  }
  if (header_size < header.size() || point_offset < header_size || point_offset > size) {
    throw bad("its header size " + std::to_string(header_size) + " and point offset " +
              std::to_string(point_offset) + " do not fit its " + std::to_string(size) + " bytes");
  }
  // Compared by division: no product of the header's numbers can wrap.
  if (count > (size - point_offset) / record_bytes) {
    throw bad("shorter than its header's " + std::to_string(count) + " points");
  }
  // The coordinate system: the WKT VLR (user "LASF_Projection", record 2112).
  std::optional<LasGridRead> grid;
  in.seekg(header_size);
  for (std::uint32_t v = 0; v < vlr_count && in; ++v) {
    std::array<char, 54> vlr{};
    in.read(vlr.data(), vlr.size());
    const auto length = field<std::uint16_t>(vlr.data(), 20);
    std::string body(length, '\0');
    in.read(body.data(), length);
    if (std::strncmp(vlr.data() + 2, "LASF_Projection", 16) == 0 &&
        field<std::uint16_t>(vlr.data(), 18) == 2112) {
      grid = grid_of_wkt(body);
    }
  }
  if (!grid) throw bad("no UTM or UPS coordinate system in its WKT record");

  ReportPoints points;
  points.source = "points.las";
  std::optional<LocalFrame> frame;
  if (origin) frame.emplace(*origin);
  in.seekg(point_offset);
  std::uint64_t index = 0;
  for_each_record(in, count, record_bytes, path, [&](const char* p) {
    std::array<double, 3> xyz{};
    for (std::size_t a = 0; a < 3; ++a) {
      xyz[a] = offset[a] + scale[a] * field<std::int32_t>(p, 4 * a);
    }
    Eigen::Vector3d enu(xyz[0] - offset[0], xyz[1] - offset[1], xyz[2] - offset[2]);
    if (frame) {
      Geodetic g;
      try {
        GeographicLib::UTMUPS::Reverse(grid->zone, grid->northp, xyz[0], xyz[1], g.lat_deg,
                                       g.lon_deg);
      } catch (const std::exception& e) {
        throw bad("point " + std::to_string(index) + ": " + e.what());
      }
      g.h_m = xyz[2];
      enu = frame->enu_from_geodetic(g);
    }
    points.add(enu.x(), enu.y(), enu.z(), std::numeric_limits<float>::quiet_NaN(),
               surface_of_asprs(static_cast<std::uint8_t>(p[16])));
    ++index;
  });
  return points;
}

}  // namespace owsim
