#include "studio/new_scenario.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <vector>

#include "geometry/error.hpp"
#include "io/trajectory/ardupilot_log_reader.hpp"
#include "io/trajectory/hellsim_reader.hpp"
#include "io/trajectory/sbet_reader.hpp"
#include "io/trajectory/trajectory_csv_reader.hpp"

namespace owsim::studio {

std::string trajectory_format_of(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".log") return "ardupilot";
  if (extension == ".csv") return "csv";
  if (extension == ".out" || extension == ".sbet") return "sbet";
  return "hellsim";
}

std::string new_scenario_yaml(const std::filesystem::path& trajectory_file,
                              const std::string& trajectory_name) {
  const std::string format = trajectory_format_of(trajectory_file);
  const std::string path = trajectory_file.string();
  std::vector<NavRecord> records;
  if (format == "ardupilot") {
    records = read_ardupilot_log(path).records;
  } else if (format == "csv") {
    records = read_trajectory_csv(path);
  } else if (format == "sbet") {
    records = read_sbet(path);
  } else {
    records = read_hellsim(path);
  }
  if (records.empty()) throw Error(path + ": no trajectory records");
  double lowest_m = records.front().position.h_m;
  for (const NavRecord& record : records) lowest_m = std::min(lowest_m, record.position.h_m);
  const Geodetic& first = records.front().position;
  const std::string name = trajectory_file.stem().string();
  // The name and file are quoted as YAML single-quoted scalars ('' for a quote).
  const auto quoted = [](const std::string& text) {
    std::string out = "'";
    for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
  };
  return fmt::format(
      "name: {}\n"
      "seed: 1\n"
      "origin: {{lat: {:.8f}, lon: {:.8f}, h: {:.2f}}}\n"
      "\n"
      "sensor:\n"
      "  model: milows\n"
      "\n"
      "trajectory:\n"
      "  file: {}\n"
      "  format: {}\n"
      "  start_s: {:.3f}\n"
      "  duration_s: {:.0f}\n"
      "\n"
      "scene:\n"
      "  terrain: {{flat_u: 0}}\n",
      quoted(name), first.lat_deg, first.lon_deg, lowest_m, quoted(trajectory_name), format,
      records.front().time_s, std::min(10.0, records.back().time_s - records.front().time_s));
}

std::string new_planned_scenario_yaml(const std::string& name) {
  return fmt::format(
      "name: {}\n"
      "seed: 1\n"
      "origin: {{lat: 48.6881, lon: 10.8447, h: 450.0}}\n"
      "\n"
      "sensor:\n"
      "  model: milows\n"
      "\n"
      "trajectory:\n"
      "  waypoints:\n"
      "    speed_mps: 40\n"
      "    points:\n"
      "      - {{e: -1200, n: 0, u: 100}}\n"
      "      - {{e: 1200, n: 0, u: 100}}\n"
      "  start_s: 0\n"
      "  duration_s: 10\n"
      "\n"
      "scene:\n"
      "  terrain: {{flat_u: 0}}\n",
      name);
}

}  // namespace owsim::studio
