#include "io/sweep/sweep_table.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/scene.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxSweepTableBytes = std::uintmax_t{256} << 20;
// The first two columns after the varied keys (write_sweep_table).
constexpr std::string_view kCountsStart[] = {"frames", "pulses"};

struct MemberRow {
  std::uint64_t frames = 0;
  std::uint64_t pulses = 0;
  std::array<std::uint64_t, kSurfaceClassCount> returns{};
  bool has_fog = false;  // the member's summary counts fog returns (a scenario with weather)
  std::uint64_t second_returns = 0;
  std::vector<std::pair<std::size_t, double>> first_seen;  // (wire column, range)
};

MemberRow read_member(const std::filesystem::path& path,
                      std::map<std::string, std::size_t>& wire_columns,
                      std::vector<std::string>& wire_ids) {
  MemberRow row;
  try {
    const nlohmann::json summary =
        nlohmann::json::parse(read_input_file(path, "member summary", std::uintmax_t{1} << 30));
    row.frames = summary.at("frames").get<std::uint64_t>();
    row.pulses = summary.at("pulses").get<std::uint64_t>();
    const nlohmann::json& returns = summary.at("returns");
    for (std::size_t c = 0; c < kSurfaceClassCount; ++c) {
      const std::string name(to_string(kSurfaceClasses[c]));
      if (kSurfaceClasses[c] == SurfaceClass::fog) {
        row.has_fog = returns.contains(name);
        if (!row.has_fog) continue;
      }
      // A summary from before the receiver's noise (owsim 0.1.0) has no false returns.
      if (kSurfaceClasses[c] == SurfaceClass::noise && !returns.contains(name)) continue;
      row.returns[c] = returns.at(name).get<std::uint64_t>();
    }
    row.second_returns = summary.at("second_returns").get<std::uint64_t>();
    for (const nlohmann::json& object : summary.at("objects")) {
      if (object.at("class") != "wire") continue;
      const std::string id = object.at("id").get<std::string>();
      const auto [at, added] = wire_columns.try_emplace(id, wire_ids.size());
      if (added) wire_ids.push_back(id);
      const nlohmann::json& range = object.at("first_seen_range_m");
      if (!range.is_null()) row.first_seen.emplace_back(at->second, range.get<double>());
    }
  } catch (const nlohmann::json::exception& e) {
    throw input_error(path.string(), std::string("not an owsim summary: ") + e.what());
  }
  return row;
}

}  // namespace

std::filesystem::path member_directory(const SweepSpec& spec, const std::filesystem::path& out,
                                       std::int64_t member) {
  return out / member_folder_name(spec, member);
}

void write_sweep_table(const SweepSpec& spec, const std::filesystem::path& out) {
  std::map<std::string, std::size_t> wire_columns;
  std::vector<std::string> wire_ids;
  std::vector<MemberRow> rows;
  rows.reserve(static_cast<std::size_t>(spec.count));
  for (std::int64_t m = 0; m < spec.count; ++m) {
    rows.push_back(
        read_member(member_directory(spec, out, m) / "summary.json", wire_columns, wire_ids));
  }
  std::string text = "member";
  for (const SweepVariation& variation : spec.vary) {
    text += ',';
    text += csv_cell(variation.key);
  }
  text += ',';
  text += kCountsStart[0];
  text += ',';
  text += kCountsStart[1];
  // The fog column where some member flew in weather: clear-air tables keep their columns.
  const bool fog =
      std::any_of(rows.begin(), rows.end(), [](const MemberRow& r) { return r.has_fog; });
  for (const SurfaceClass surface : kSurfaceClasses) {
    if (surface == SurfaceClass::fog && !fog) continue;
    text += ",returns_";
    text += to_string(surface);
  }
  text += ",second_returns";
  for (const std::string& id : wire_ids) {
    text += ',';
    text += csv_cell("first_seen_range_m[" + id + "]");
  }
  text += '\n';
  for (std::int64_t m = 0; m < spec.count; ++m) {
    const MemberRow& row = rows[static_cast<std::size_t>(m)];
    append_csv_integer(text, m);
    for (const std::string& value : member_values(spec, m)) {
      text += ',';
      text += csv_cell(value);
    }
    for (const std::uint64_t count : {row.frames, row.pulses}) {
      text += ',';
      append_csv_integer(text, static_cast<std::int64_t>(count));
    }
    for (std::size_t c = 0; c < kSurfaceClassCount; ++c) {
      if (kSurfaceClasses[c] == SurfaceClass::fog && !fog) continue;
      text += ',';
      append_csv_integer(text, static_cast<std::int64_t>(row.returns[c]));
    }
    text += ',';
    append_csv_integer(text, static_cast<std::int64_t>(row.second_returns));
    std::vector<std::optional<double>> ranges(wire_ids.size());
    for (const auto& [column, range] : row.first_seen) ranges[column] = range;
    for (const std::optional<double>& range : ranges) {
      text += ',';
      if (range) append_csv_fixed(text, *range, 4);
    }
    text += '\n';
  }
  AtomicOutputFile file(out / "sweep.csv");
  file.write(text);
  file.commit();
}

std::vector<std::string> read_sweep_values(const std::filesystem::path& sweep_csv,
                                           std::string_view key) {
  const std::string text = read_input_file(sweep_csv, "sweep table", kMaxSweepTableBytes);
  std::vector<std::string_view> cells;
  std::size_t column = 0;
  std::vector<std::string> values;
  for_each_line(text, [&](std::int64_t line, std::string_view row) {
    if (line == 1) {
      split_csv_cells(row, cells);
      // The counts start at the last "frames,pulses": a varied key may itself be named frames.
      std::size_t counts = 0;
      for (std::size_t c = 1; c + 1 < cells.size(); ++c) {
        if (cells[c] == kCountsStart[0] && cells[c + 1] == kCountsStart[1]) counts = c;
      }
      if (cells.empty() || cells.front() != "member" || counts == 0) {
        throw input_error(sweep_csv.string() + ":1", "not an owsim sweep table");
      }
      std::string varied;
      for (std::size_t c = 1; c < counts; ++c) {
        const std::string name = csv_cell_text(cells[c]);
        if (name == key) column = c;
        varied += (varied.empty() ? "" : ", ") + name;
      }
      if (column == 0) {
        throw input_error(sweep_csv.string() + ": " + std::string(key),
                          "the sweep does not vary this key (it varies " +
                              (varied.empty() ? std::string("none") : varied) + ")");
      }
      return;
    }
    if (row.empty()) return;
    split_csv_cells(row, cells);
    if (cells.size() <= column) {
      throw input_error(sweep_csv.string() + ":" + std::to_string(line),
                        "no cell for " + std::string(key));
    }
    values.push_back(csv_cell_text(cells[column]));
  });
  if (column == 0) throw input_error(sweep_csv.string(), "empty: no header");
  return values;
}

}  // namespace owsim
