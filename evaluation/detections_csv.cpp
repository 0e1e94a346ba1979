#include "evaluation/detections_csv.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"
#include "io/files/utf8_text.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxDetectionsBytes = std::uintmax_t{256} << 20;
constexpr std::size_t kMaxTextCell = 256;  // class and track

enum Column : std::size_t { kTime, kE, kN, kU, kLat, kLon, kH, kClass, kTrack, kColumns };
constexpr std::array<std::string_view, kColumns> kNames = {
    "time_s", "e_m", "n_m", "u_m", "lat_deg", "lon_deg", "h_m", "class", "track"};

[[noreturn]] void refuse(const std::string& where, std::string_view column,
                         const std::string& problem) {
  throw input_error(where, std::string(column) + ": " + problem);
}

double finite_number(std::string_view cell, const std::string& where, std::string_view column) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (error != std::errc() || end != cell.data() + cell.size() || !std::isfinite(value)) {
    refuse(where, column, "not a finite number: '" + std::string(cell.substr(0, 40)) + "'");
  }
  return value;
}

// A position the scorer can use: within kMaxDetectionDistanceM of the origin (NaN is not).
void require_near_origin(const Eigen::Vector3d& enu_m, const std::string& where,
                         std::string_view columns) {
  const double distance_m = enu_m.norm();
  if (distance_m <= kMaxDetectionDistanceM) return;
  refuse(where, columns,
         number_text(distance_m / 1000.0, 6) + " km from the scenario origin (at most " +
             number_text(kMaxDetectionDistanceM / 1000.0, 6) + " km)");
}

}  // namespace

void read_detections_csv(const std::filesystem::path& path, const DetectionFlight& flight,
                         const std::function<void(const Detection&)>& each) {
  const std::string text = read_input_file(path, "detections file", kMaxDetectionsBytes);
  const double earliest_s = flight.start_s - kDetectionTimeMarginS;
  const double latest_s = flight.end_s + kDetectionTimeMarginS;
  std::array<std::optional<std::size_t>, kColumns> position;
  std::vector<std::string_view> cells;
  bool geodetic = false;
  Detection detection;
  for_each_line(text, [&](std::int64_t line, std::string_view row) {
    const std::string where = path.string() + ":" + std::to_string(line);
    if (line == 1) {
      split_csv_cells(row, cells);
      for (std::size_t cell = 0; cell < cells.size(); ++cell) {
        const std::string name = csv_cell_text(cells[cell]);
        for (std::size_t c = 0; c < kColumns; ++c) {
          if (name != kNames[c]) continue;
          if (position[c]) throw input_error(where, "column '" + name + "' appears twice");
          position[c] = cell;
        }
      }
      const bool local = position[kE] && position[kN] && position[kU];
      geodetic = position[kLat] && position[kLon] && position[kH];
      if (!position[kTime] || local == geodetic) {
        throw input_error(where,
                          "the header needs time_s and either e_m,n_m,u_m or lat_deg,lon_deg,h_m "
                          "(optionally class, track)");
      }
      return;
    }
    if (row.empty()) return;
    split_csv_cells(row, cells);
    const auto cell = [&](Column c) -> std::string_view {
      if (*position[c] >= cells.size()) {
        refuse(where, kNames[c], "missing (" + std::to_string(cells.size()) + " cells)");
      }
      return cells[*position[c]];
    };
    detection.line = line;
    detection.time_s = finite_number(cell(kTime), where, "time_s");
    if (!(detection.time_s >= earliest_s && detection.time_s <= latest_s)) {
      refuse(where, "time_s",
             number_text(detection.time_s) + " s is outside the flight (" +
                 number_text(flight.start_s) + " to " + number_text(flight.end_s) + " s, ±" +
                 number_text(kDetectionTimeMarginS) + " s)");
    }
    if (geodetic) {
      const double lat = finite_number(cell(kLat), where, "lat_deg");
      const double lon = finite_number(cell(kLon), where, "lon_deg");
      const double h = finite_number(cell(kH), where, "h_m");
      if (!(std::abs(lat) <= 90.0))
        refuse(where, "lat_deg", number_text(lat) + "° is outside ±90°");
      if (!(std::abs(lon) <= 360.0)) {
        refuse(where, "lon_deg", number_text(lon) + "° is outside ±360°");
      }
      if (!(std::abs(h) <= kMaxDetectionDistanceM)) {
        refuse(where, "h_m", number_text(h) + " m is outside ±1,000 km");
      }
      detection.enu_m = flight.frame.enu_from_geodetic({lat, lon, h});
      require_near_origin(detection.enu_m, where, "lat_deg,lon_deg,h_m");
    } else {
      detection.enu_m = {finite_number(cell(kE), where, "e_m"),
                         finite_number(cell(kN), where, "n_m"),
                         finite_number(cell(kU), where, "u_m")};
      require_near_origin(detection.enu_m, where, "e_m,n_m,u_m");
    }
    for (const Column column : {kClass, kTrack}) {
      std::string& target = column == kClass ? detection.object_class : detection.track;
      target.clear();
      if (!position[column]) continue;
      target = csv_cell_text(cell(column));
      if (target.size() > kMaxTextCell) refuse(where, kNames[column], "longer than 256 bytes");
      if (const auto bad = invalid_utf8_offset(target)) {
        refuse(where, kNames[column], "not UTF-8 (byte " + std::to_string(*bad + 1) + ")");
      }
    }
    each(detection);
  });
  if (position[kTime] == std::nullopt) throw input_error(path.string(), "empty: no header");
}

}  // namespace owsim
