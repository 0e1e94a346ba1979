#include "io/trajectory/ardupilot_log_reader.hpp"

#include <cmath>
#include <fstream>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/input_file.hpp"
#include "io/trajectory/trajectory_text.hpp"
#include "sensor/cubic_spline.hpp"

namespace owsim {
namespace {

struct GpsLine {
  double time_ms = 0;
  bool fix = false;
  Geodetic position;
};

struct AttLine {
  GpsLine gps;  // the GPS line logged before it
  Attitude attitude;
};

std::vector<std::string_view> message_fields(std::string_view line, std::size_t expected,
                                             const std::string& where) {
  const std::vector<std::string_view> fields = split_fields(line.substr(4), ',');
  if (fields.size() != expected) {
    throw input_error(
        where, "expected " + std::to_string(expected) + " comma-separated fields after '" +
                   std::string(line.substr(0, 4)) + "', found " + std::to_string(fields.size()));
  }
  return fields;
}

}  // namespace

ArduPilotLog read_ardupilot_log(const std::string& path, const ArduPilotLogOptions& options) {
  require_input_file(path, "ArduPilot log", kMaxTrajectoryBytes);
  std::ifstream file(path);
  if (!file) throw file_error(path, "cannot open the ArduPilot log");
  ArduPilotLog log;
  std::vector<AttLine> lines;
  GpsLine gps;
  bool have_gps = false, in_dropout = false;
  std::string text;
  std::size_t line_number = 0;
  while (std::getline(file, text)) {
    ++line_number;
    const std::string_view line = trim(text);
    const std::string where = path + ":" + std::to_string(line_number);
    if (line.starts_with("GPS:")) {
      const std::vector<std::string_view> f = message_fields(line, 10, where);
      GpsLine next;
      next.time_ms = finite_field(f[0], path, line_number, "GPS time");
      next.fix = finite_field(f[1], path, line_number, "fix") != 0.0;
      next.position = {
          finite_field(f[3], path, line_number, "latitude"),
          finite_field(f[4], path, line_number, "longitude"),
          finite_field(f[7], path, line_number, "GPS altitude") + options.geoid_separation_m};
      if (have_gps && next.time_ms < gps.time_ms) {
        throw input_error(where, "GPS time " + std::string(f[0]) + " ms goes back");
      }
      if (next.fix) validate_geodetic(next.position, where);
      ++log.gps_lines;
      if (!next.fix) ++log.no_fix_lines;
      if (!next.fix && !in_dropout) ++log.dropouts;
      in_dropout = !next.fix;
      gps = next;
      have_gps = true;
    } else if (line.starts_with("ATT:")) {
      const std::vector<std::string_view> f = message_fields(line, 3, where);
      ++log.att_lines;
      const Attitude attitude{finite_field(f[0], path, line_number, "roll") / 100.0,
                              finite_field(f[1], path, line_number, "pitch") / 100.0,
                              finite_field(f[2], path, line_number, "yaw") / 100.0};
      if (have_gps) {
        lines.push_back({gps, attitude});
      } else {
        ++log.dropped_records;
      }
    }
  }

  // Group by GPS time; time each record; collect one fix per GPS time.
  std::vector<double> time_s(lines.size());
  std::vector<double> fix_time_s, fix_lat, fix_lon, fix_h;
  const double zero_ms = lines.empty() ? 0.0 : lines.front().gps.time_ms;
  double previous_step_ms = 0.0;
  for (std::size_t first = 0; first < lines.size();) {
    std::size_t end = first;
    while (end < lines.size() && lines[end].gps.time_ms == lines[first].gps.time_ms) ++end;
    const double group_ms = lines[first].gps.time_ms;
    const std::size_t count = end - first;
    const double step_ms =
        end < lines.size() ? (lines[end].gps.time_ms - group_ms) / double(count) : previous_step_ms;
    for (std::size_t j = 0; j < count; ++j) {
      time_s[first + j] = (group_ms - zero_ms + double(j) * step_ms) / 1000.0;
    }
    for (std::size_t j = first; j < end; ++j) {
      if (!lines[j].gps.fix) continue;
      fix_time_s.push_back((group_ms - zero_ms) / 1000.0);
      fix_lat.push_back(lines[j].gps.position.lat_deg);
      fix_lon.push_back(lines[j].gps.position.lon_deg);
      fix_h.push_back(lines[j].gps.position.h_m);
      break;
    }
    previous_step_ms = step_ms;
    first = end;
  }
  if (fix_time_s.size() < 2) {
    throw input_error(path, "holds " + std::to_string(fix_time_s.size()) +
                                " distinct GPS fixes; a trajectory needs at least two");
  }

  const CubicSpline lat(fix_time_s, fix_lat), lon(fix_time_s, fix_lon), h(fix_time_s, fix_h);
  const double first_fix_s = fix_time_s.front(), last_fix_s = fix_time_s.back();
  double kept_zero_s = 0.0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (time_s[i] < first_fix_s || time_s[i] > last_fix_s) {
      ++log.dropped_records;
      continue;
    }
    if (log.records.empty()) kept_zero_s = time_s[i];
    NavRecord record;
    record.time_s = time_s[i];
    record.position = {lat.value(time_s[i]), lon.value(time_s[i]), h.value(time_s[i])};
    record.attitude = lines[i].attitude;
    log.records.push_back(record);
  }
  for (NavRecord& record : log.records) record.time_s -= kept_zero_s;
  for (std::size_t k = 0; k < fix_time_s.size(); ++k) {
    log.fixes.push_back({fix_time_s[k] - kept_zero_s, {fix_lat[k], fix_lon[k], fix_h[k]}});
  }
  log.gps_time_of_week_at_zero_s = (zero_ms / 1000.0) + kept_zero_s;
  return log;
}

}  // namespace owsim
