#include "io/report/report_evidence.hpp"

#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxEvidenceBytes = std::uintmax_t{256} << 20;
constexpr std::size_t kPdColumns = 13;  // target and twelve numbers

nlohmann::json parse_json(const std::filesystem::path& path, std::string_view what) {
  try {
    return nlohmann::json::parse(read_input_file(path, what, kMaxEvidenceBytes));
  } catch (const nlohmann::json::exception& e) {
    throw input_error(path.string(),
                      std::string("not an owsim ") + std::string(what) + ": " + e.what());
  }
}

// pd.csv's numbers by bin; an empty cell (no count) is null.
nlohmann::json pd_bins(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, "pd table", kMaxEvidenceBytes);
  nlohmann::json bins = nlohmann::json::array();
  std::vector<std::string_view> cells;
  for_each_line(text, [&](std::int64_t line, std::string_view row) {
    if (line == 1 || row.empty()) return;
    split_csv_cells(row, cells);
    const std::string where = path.string() + ":" + std::to_string(line);
    if (cells.size() != kPdColumns) throw input_error(where, "not a row of owsim pd");
    nlohmann::json numbers = nlohmann::json::array();
    for (std::size_t c = 1; c < kPdColumns; ++c) {
      double value = 0.0;
      const auto [stop, error] =
          std::from_chars(cells[c].data(), cells[c].data() + cells[c].size(), value);
      if (cells[c].empty()) {
        numbers.push_back(nullptr);
      } else if (error != std::errc() || stop != cells[c].data() + cells[c].size() ||
                 !std::isfinite(value)) {
        throw input_error(where, "not a row of owsim pd");
      } else {
        numbers.push_back(value);
      }
    }
    bins.push_back(std::move(numbers));
  });
  return bins;
}

}  // namespace

nlohmann::json report_evidence_json(const std::filesystem::path& folder, std::size_t max_objects) {
  nlohmann::json evidence = {{"pd", nullptr}, {"roc", nullptr}, {"score", nullptr}};
  std::error_code error;
  if (std::filesystem::is_regular_file(folder / "pd.json", error) &&
      std::filesystem::is_regular_file(folder / "pd.csv", error)) {
    nlohmann::json pd = parse_json(folder / "pd.json", "pd summary");
    if (!pd.is_object()) throw input_error((folder / "pd.json").string(), "not an object");
    pd["rows"] = pd_bins(folder / "pd.csv");
    evidence["pd"] = std::move(pd);
  }
  if (std::filesystem::is_regular_file(folder / "roc.json", error)) {
    nlohmann::json roc = parse_json(folder / "roc.json", "roc summary");
    if (!roc.is_object() || !roc.contains("rows") || !roc["rows"].is_array()) {
      throw input_error((folder / "roc.json").string(), "not an owsim roc summary (no rows)");
    }
    evidence["roc"] = std::move(roc);
  }
  if (std::filesystem::is_regular_file(folder / "score.json", error)) {
    nlohmann::json score = parse_json(folder / "score.json", "score");
    if (!score.is_object()) throw input_error((folder / "score.json").string(), "not an object");
    if (score.contains("objects") && score["objects"].is_array()) {
      nlohmann::json& objects = score["objects"];
      score["objects_total"] = objects.size();
      if (objects.size() > max_objects) {
        objects.erase(objects.begin() + static_cast<std::ptrdiff_t>(max_objects), objects.end());
      }
    }
    evidence["score"] = std::move(score);
  }
  return evidence;
}

}  // namespace owsim
