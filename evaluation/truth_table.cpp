#include "evaluation/truth_table.hpp"

#include <charconv>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"
#include "io/run/truth_csv.hpp"
#include "io/sweep/sweep_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxSummaryBytes = std::uintmax_t{1} << 30;
constexpr std::uintmax_t kMaxSweepTableBytes = std::uintmax_t{256} << 20;

enum Column : std::size_t {
  kFrame,
  kTime,
  kObject,
  kClass,
  kRange,
  kAlpha,
  kBeta,
  kInView,
  kReturns,
  kClosing,
  kReach,
  kColumns
};

template <typename T>
T number_in(std::string_view cell, const std::string& where, std::string_view column) {
  T value{};
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (error != std::errc() || end != cell.data() + cell.size()) {
    throw input_error(where, std::string(column) + ": not a number: '" + std::string(cell) + "'");
  }
  return value;
}

}  // namespace

std::vector<CampaignFlight> campaign_flights(const std::filesystem::path& directory) {
  std::error_code error;
  const std::filesystem::path table = directory / "sweep.csv";
  if (std::filesystem::is_regular_file(table, error)) {
    const std::string text = read_input_file(table, "sweep table", kMaxSweepTableBytes);
    std::vector<std::int64_t> numbers;
    std::vector<std::string_view> cells;
    for_each_line(text, [&](std::int64_t line, std::string_view row) {
      if (line == 1) {
        split_csv_cells(row, cells);
        if (cells.empty() || cells.front() != "member") {
          throw input_error(table.string() + ":1", "not an owsim sweep table (no member column)");
        }
        return;
      }
      if (row.empty()) return;
      split_csv_cells(row, cells);
      const std::string_view member = cells.front();
      std::int64_t number = -1;
      const auto [parsed_to, failed] =
          std::from_chars(member.data(), member.data() + member.size(), number);
      if (failed != std::errc() || parsed_to != member.data() + member.size() || number < 0) {
        throw input_error(table.string() + ":" + std::to_string(line),
                          "member '" + std::string(member) + "' is not a member number");
      }
      numbers.push_back(number);
    });
    if (numbers.empty()) throw input_error(table.string(), "lists no member");
    // Member folders are named as owsim sweep names them: zero-padded to the widest number.
    const auto count = static_cast<std::int64_t>(numbers.size());
    std::vector<CampaignFlight> members;
    for (const std::int64_t number : numbers) {
      const std::string name = member_folder_name(count, number);
      members.push_back({name, directory / name});
    }
    return members;
  }
  if (std::filesystem::is_regular_file(directory / "summary.json", error)) {
    const std::filesystem::path absolute = std::filesystem::absolute(directory).lexically_normal();
    std::string name = absolute.filename().string();
    if (name.empty()) name = absolute.parent_path().filename().string();
    return {{name, directory}};
  }
  throw input_error(directory.string(),
                    "neither a run folder (summary.json) nor a sweep folder (sweep.csv)");
}

FlightFacts read_flight_facts(const std::filesystem::path& summary_json) {
  const std::string text = read_input_file(summary_json, "run summary", kMaxSummaryBytes);
  FlightFacts facts;
  try {
    const nlohmann::json summary = nlohmann::json::parse(text);
    facts.frames = summary.at("frames").get<std::int64_t>();
    if (!summary.contains("frame_period_s")) {
      throw Error("no frame_period_s (written by an owsim before 0.2: run the flight again)");
    }
    facts.frame_period_s = summary.at("frame_period_s").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw input_error(summary_json.string(), std::string("not an owsim summary: ") + e.what());
  } catch (const Error& e) {
    throw input_error(summary_json.string(), e.what());
  }
  if (facts.frames < 1 || !(facts.frame_period_s > 0.0)) {
    throw input_error(summary_json.string(), "frames or frame_period_s out of range");
  }
  return facts;
}

std::vector<ObjectTrack> read_truth_csv(
    const std::filesystem::path& truth_csv,
    const std::function<bool(std::string_view id, std::string_view object_class)>& wanted) {
  std::error_code error;
  if (!std::filesystem::exists(truth_csv, error)) {
    throw input_error(truth_csv.string(),
                      "missing: the run wrote no ground truth (add truth to its outputs)");
  }
  require_input_file(truth_csv, "ground truth");
  std::ifstream in(truth_csv, std::ios::binary);
  if (!in) throw file_error(truth_csv.string(), "cannot open the ground truth");
  std::vector<ObjectTrack> tracks;
  std::map<std::string, std::size_t, std::less<>> track_of;
  std::map<std::string, bool, std::less<>> decided;  // id → wanted
  std::string line;
  std::vector<std::string_view> cells;
  std::int64_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = truth_csv.string() + ":" + std::to_string(number);
    if (number == 1) {
      if (line != kTruthCsvHeader) {
        throw input_error(where, "not an owsim truth.csv header (expected '" +
                                     std::string(kTruthCsvHeader) + "')");
      }
      continue;
    }
    if (line.empty()) continue;
    split_csv_cells(line, cells);
    if (cells.size() != kColumns) {
      throw input_error(
          where, std::to_string(cells.size()) + " cells, expected " + std::to_string(kColumns));
    }
    const std::string id = csv_cell_text(cells[kObject]);
    auto known = decided.find(id);
    if (known == decided.end()) {
      known = decided.emplace(id, wanted(id, cells[kClass])).first;
      if (known->second) {
        track_of.emplace(id, tracks.size());
        tracks.push_back({id, std::string(cells[kClass]), {}});
      }
    }
    if (!known->second) continue;
    TruthEntry entry;
    entry.frame = number_in<std::int64_t>(cells[kFrame], where, "frame");
    entry.time_s = number_in<double>(cells[kTime], where, "time_s");
    entry.range_m = number_in<double>(cells[kRange], where, "range_m");
    const auto in_view = number_in<int>(cells[kInView], where, "in_view");
    if (in_view != 0 && in_view != 1) throw input_error(where, "in_view: expected 0 or 1");
    entry.in_view = in_view == 1;
    entry.returns = number_in<std::uint64_t>(cells[kReturns], where, "returns");
    entry.closing_speed_mps = number_in<double>(cells[kClosing], where, "closing_speed_mps");
    std::vector<TruthEntry>& rows = tracks[track_of.find(id)->second].rows;
    if (!rows.empty() && entry.frame <= rows.back().frame) {
      throw input_error(where, "frame " + std::to_string(entry.frame) + " of '" + id +
                                   "' after frame " + std::to_string(rows.back().frame));
    }
    rows.push_back(entry);
  }
  if (number == 0) throw input_error(truth_csv.string(), "empty: no header");
  return tracks;
}

}  // namespace owsim
