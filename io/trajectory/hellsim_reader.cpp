#include "io/trajectory/hellsim_reader.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/input_file.hpp"
#include "io/trajectory/trajectory_text.hpp"

namespace owsim {
namespace {

constexpr std::size_t kHellsimColumns = 15;
constexpr std::array<std::string_view, kHellsimColumns> kHellsimColumnNames = {
    "Pic #", "Time-Tag", "Heading", "Pitch", "Roll",     "X-Vel", "Y-Vel",   "Z-Vel",
    "N-Vel", "E-Vel",    "D-Vel",   "Veloc", "Latitude", "Long.", "Altitude"};
// The fields read, by their index (a scoped name: these sources build together, CMakeLists.txt).
struct HellsimColumn {
  enum : std::size_t { tag = 1, heading = 2, pitch = 3, roll = 4, lat = 12, lon = 13, alt = 14 };
};

bool is_header_or_comment(std::string_view first_field) {
  return first_field.starts_with('#') || first_field.starts_with("Pic") ||
         first_field.starts_with("pic");
}

}  // namespace

std::vector<NavRecord> read_hellsim(const std::string& path, const HellSimOptions& options) {
  if (!(std::isfinite(options.tick_s) && options.tick_s > 0)) {
    throw input_error(path,
                      "the HellSim tick weight (tick_s) must be a positive number of seconds");
  }
  require_input_file(path, "HellSim trajectory file", kMaxTrajectoryBytes);
  std::ifstream file(path);
  if (!file) throw file_error(path, "cannot open the HellSim trajectory file");
  std::vector<NavRecord> records;
  std::string line;
  std::size_t line_number = 0;
  double first_tag = 0, previous_tag = 0, unwrapped_tag = 0;
  while (std::getline(file, line)) {
    ++line_number;
    const std::vector<std::string_view> fields = split_whitespace(line);
    if (fields.empty() || is_header_or_comment(fields.front())) continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (fields.size() != kHellsimColumns) {
      throw input_error(where, "expected " + std::to_string(kHellsimColumns) +
                                   " whitespace-separated columns (Pic # … Altitude), found " +
                                   std::to_string(fields.size()));
    }
    std::array<double, kHellsimColumns> value{};
    for (std::size_t c = 0; c < kHellsimColumns; ++c) {
      value[c] = finite_field(fields[c], path, line_number, kHellsimColumnNames[c]);
    }
    const double tag_value = value[HellsimColumn::tag];
    if (tag_value < 0 || tag_value != std::floor(tag_value)) {
      throw input_error(
          where, "Time-Tag '" + std::string(fields[HellsimColumn::tag]) + "' is not a whole count");
    }
    if (records.empty()) {
      first_tag = unwrapped_tag = tag_value;
    } else {
      double step = tag_value - previous_tag;
      const auto modulus = static_cast<double>(options.tag_modulus);
      if (step < 0 && options.tag_modulus > 0 && step + modulus <= 0.5 * modulus) step += modulus;
      if (step == 0) {
        throw input_error(where, "Time-Tag " + std::string(fields[HellsimColumn::tag]) +
                                     " repeats the previous record's");
      }
      if (step < 0) {
        throw input_error(where, "Time-Tag " + std::string(fields[HellsimColumn::tag]) +
                                     " goes back from the previous record's " +
                                     std::to_string(std::llround(previous_tag)) +
                                     " (more than a counter wrap explains)");
      }
      unwrapped_tag += step;
    }
    previous_tag = tag_value;
    NavRecord record;
    record.time_s = (unwrapped_tag - first_tag) * options.tick_s;
    record.position = {value[HellsimColumn::lat], value[HellsimColumn::lon],
                       value[HellsimColumn::alt]};
    record.attitude = {value[HellsimColumn::roll], value[HellsimColumn::pitch],
                       value[HellsimColumn::heading]};
    validate_geodetic(record.position, where);
    records.push_back(record);
  }
  if (records.empty()) throw input_error(path, "holds no navigation records");
  return records;
}

}  // namespace owsim
