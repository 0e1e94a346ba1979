#include "evaluation/detections_csv.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxDetectionsBytes = std::uintmax_t{2} << 30;
constexpr std::size_t kMaxTextCell = 256;  // class and track

enum Column : std::size_t { kTime, kE, kN, kU, kLat, kLon, kH, kClass, kTrack, kColumns };
constexpr std::array<std::string_view, kColumns> kNames = {
    "time_s", "e_m", "n_m", "u_m", "lat_deg", "lon_deg", "h_m", "class", "track"};

double finite_number(std::string_view cell, const std::string& where, std::string_view column) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (error != std::errc() || end != cell.data() + cell.size() || !std::isfinite(value)) {
    throw input_error(where, std::string(column) + ": not a finite number: '" +
                                 std::string(cell.substr(0, 40)) + "'");
  }
  return value;
}

}  // namespace

std::vector<Detection> read_detections_csv(const std::filesystem::path& path,
                                           const LocalFrame& frame) {
  const std::string text = read_input_file(path, "detections file", kMaxDetectionsBytes);
  std::array<std::optional<std::size_t>, kColumns> position;
  std::vector<Detection> detections;
  std::vector<std::string_view> cells;
  bool geodetic = false;
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
        throw input_error(where, std::string(kNames[c]) + ": missing (" +
                                     std::to_string(cells.size()) + " cells)");
      }
      return cells[*position[c]];
    };
    Detection detection;
    detection.line = line;
    detection.time_s = finite_number(cell(kTime), where, "time_s");
    if (geodetic) {
      const double lat = finite_number(cell(kLat), where, "lat_deg");
      const double lon = finite_number(cell(kLon), where, "lon_deg");
      const double h = finite_number(cell(kH), where, "h_m");
      if (std::abs(lat) > 90.0 || std::abs(lon) > 540.0 || std::abs(h) > 1e5) {
        throw input_error(where, "lat_deg, lon_deg, h_m: out of range");
      }
      detection.enu_m = frame.enu_from_geodetic({lat, lon, h});
    } else {
      detection.enu_m = {finite_number(cell(kE), where, "e_m"),
                         finite_number(cell(kN), where, "n_m"),
                         finite_number(cell(kU), where, "u_m")};
      if (detection.enu_m.cwiseAbs().maxCoeff() > 1e6) {
        throw input_error(where, "e_m, n_m, u_m: farther than 1,000 km from the origin");
      }
    }
    for (const auto& [column, target] :
         {std::pair{kClass, &detection.object_class}, std::pair{kTrack, &detection.track}}) {
      if (!position[column]) continue;
      *target = csv_cell_text(cell(column));
      if (target->size() > kMaxTextCell) {
        throw input_error(where, std::string(kNames[column]) + ": longer than 256 characters");
      }
    }
    detections.push_back(std::move(detection));
  });
  if (position[kTime] == std::nullopt) throw input_error(path.string(), "empty: no header");
  return detections;
}

}  // namespace owsim
