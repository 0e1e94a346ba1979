#include "io/trajectory/trajectory_csv_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"
#include "io/trajectory/trajectory_text.hpp"

namespace owsim {
namespace {

constexpr std::size_t kNeeded = 7;
constexpr std::array<std::string_view, kNeeded> kCsvColumnNames = {
    "time_s", "lat_deg", "lon_deg", "h_m", "roll_deg", "pitch_deg", "heading_deg"};

std::string header_name(std::string_view field) {
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') {
    field = trim(field.substr(1, field.size() - 2));
  }
  std::string name(field);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

// Which cell of a row holds each needed column.
std::array<std::size_t, kNeeded> column_positions(std::string_view header,
                                                  const std::string& where) {
  constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);
  std::array<std::size_t, kNeeded> position;
  position.fill(kAbsent);
  const std::vector<std::string_view> fields = split_fields(header, ',');
  for (std::size_t cell = 0; cell < fields.size(); ++cell) {
    const std::string name = header_name(fields[cell]);
    for (std::size_t c = 0; c < kNeeded; ++c) {
      if (name != kCsvColumnNames[c]) continue;
      if (position[c] != kAbsent) {
        throw input_error(where, "column '" + name + "' appears twice in the header");
      }
      position[c] = cell;
    }
  }
  for (std::size_t c = 0; c < kNeeded; ++c) {
    if (position[c] == kAbsent) {
      throw input_error(where, "the header has no column '" + std::string(kCsvColumnNames[c]) +
                                   "' (needs time_s, lat_deg, lon_deg, h_m, roll_deg, pitch_deg, "
                                   "heading_deg)");
    }
  }
  return position;
}

}  // namespace

std::vector<NavRecord> read_trajectory_csv(const std::string& path) {
  require_input_file(path, "CSV trajectory file", kMaxTrajectoryBytes);
  std::ifstream file(path);
  if (!file) throw file_error(path, "cannot open the CSV trajectory file");
  std::vector<NavRecord> records;
  std::array<std::size_t, kNeeded> position{};
  bool have_header = false;
  std::size_t cells_needed = 0;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(file, line)) {
    ++line_number;
    if (line_number == 1) line.erase(0, line.size() - without_utf8_bom(line).size());
    if (trim(line).empty()) continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (!have_header) {
      position = column_positions(line, where);
      cells_needed = *std::max_element(position.begin(), position.end()) + 1;
      have_header = true;
      continue;
    }
    const std::vector<std::string_view> cells = split_fields(line, ',');
    if (cells.size() < cells_needed) {
      throw input_error(where, "expected at least " + std::to_string(cells_needed) +
                                   " comma-separated cells, found " + std::to_string(cells.size()));
    }
    std::array<double, kNeeded> value{};
    for (std::size_t c = 0; c < kNeeded; ++c) {
      value[c] = finite_field(cells[position[c]], path, line_number, kCsvColumnNames[c]);
    }
    NavRecord record;
    record.time_s = value[0];
    record.position = {value[1], value[2], value[3]};
    record.attitude = {value[4], value[5], value[6]};
    validate_geodetic(record.position, where);
    if (!records.empty() && !(record.time_s > records.back().time_s)) {
      throw input_error(where, "time_s '" + std::string(trim(cells[position[0]])) +
                                   "' is not after the previous record's");
    }
    records.push_back(record);
  }
  if (!have_header) throw input_error(path, "is empty: no header line");
  if (records.empty()) throw input_error(path, "holds a header but no records");
  return records;
}

}  // namespace owsim
