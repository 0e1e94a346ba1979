#include "io/report/report_trajectory.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <fstream>
#include <string>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"

namespace owsim {

ReportTrajectory read_report_trajectory(const std::filesystem::path& path) {
  static constexpr std::array<std::string_view, 10> kNames = {
      "time_s", "lat_deg", "lon_deg",  "h_m",       "e_m",
      "n_m",    "u_m",     "roll_deg", "pitch_deg", "heading_deg"};
  std::ifstream in(path);
  if (!in) throw file_error(path.string(), "cannot open for reading");
  ReportTrajectory out;
  std::array<std::size_t, kNames.size()> index{};
  std::vector<std::string_view> cells;
  std::string line;
  for (std::uint64_t number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) line.erase(0, line.size() - without_utf8_bom(line).size());
    split_csv_cells(line, cells);
    const std::string where = path.string() + ":" + std::to_string(number);
    if (number == 1) {
      for (std::size_t c = 0; c < kNames.size(); ++c) {
        const auto it = std::find(cells.begin(), cells.end(), kNames[c]);
        if (it == cells.end()) throw input_error(where, "no column " + std::string(kNames[c]));
        index[c] = static_cast<std::size_t>(it - cells.begin());
      }
      continue;
    }
    if (line.empty()) continue;
    std::array<double, kNames.size()> row{};
    for (std::size_t c = 0; c < kNames.size(); ++c) {
      const std::string_view cell = index[c] < cells.size() ? cells[index[c]] : std::string_view();
      const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), row[c]);
      if (error != std::errc() || end != cell.data() + cell.size() || cell.empty()) {
        throw input_error(where,
                          std::string(kNames[c]) + ": '" + std::string(cell) + "' is not a number");
      }
    }
    out.rows.push_back(
        {row[0], row[1], row[2], row[3], row[4], row[5], row[6], row[7], row[8], row[9]});
  }
  if (in.bad()) throw file_error(path.string(), "read error");
  return out;
}

}  // namespace owsim
