#include "io/run/output_kind.hpp"

#include <algorithm>
#include <utility>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr std::pair<OutputKind, std::string_view> kNames[] = {
    {OutputKind::d64, "d64"},
    {OutputKind::csv, "csv"},
    {OutputKind::las, "las"},
    {OutputKind::ply, "ply"},
    {OutputKind::trajectory, "trajectory"},
    {OutputKind::summary, "summary"},
    {OutputKind::truth, "truth"},
    {OutputKind::quicklook, "quicklook"},
    {OutputKind::mcap, "mcap"},
    {OutputKind::detections, "detections"}};
constexpr OutputKind kPointKinds[] = {OutputKind::csv, OutputKind::las, OutputKind::ply};

}  // namespace

std::set<OutputKind> all_outputs() {
  std::set<OutputKind> kinds;
  for (const auto& [kind, name] : kNames) kinds.insert(kind);
  kinds.erase(OutputKind::mcap);  // asked for by name only
  kinds.erase(OutputKind::detections);
  return kinds;
}

std::set<OutputKind> parse_output_list(std::string_view list) {
  std::set<OutputKind> kinds;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string_view item = list.substr(begin, comma - begin);
    begin = comma + 1;
    if (item == "points") {
      kinds.insert(std::begin(kPointKinds), std::end(kPointKinds));
      continue;
    }
    const auto* known = std::find_if(std::begin(kNames), std::end(kNames),
                                     [&](const auto& entry) { return entry.second == item; });
    if (known == std::end(kNames)) {
      throw input_error("--outputs",
                        "unknown output '" + std::string(item) +
                            "' (expected d64, points, csv, las, ply, trajectory, summary, "
                            "truth, quicklook, mcap, detections)");
    }
    kinds.insert(known->first);
    if (known->first == OutputKind::detections) kinds.insert(OutputKind::d64);  // it reads them
  }
  return kinds;
}

std::string output_list(const std::set<OutputKind>& outputs) {
  const bool all_points = std::all_of(std::begin(kPointKinds), std::end(kPointKinds),
                                      [&](OutputKind kind) { return outputs.contains(kind); });
  std::string list;
  for (const auto& [kind, name] : kNames) {
    if (!outputs.contains(kind)) continue;
    const bool point_file =
        kind == OutputKind::csv || kind == OutputKind::las || kind == OutputKind::ply;
    if (all_points && point_file && kind != OutputKind::csv) continue;
    if (!list.empty()) list += ',';
    list += all_points && point_file ? std::string_view("points") : name;
  }
  return list;
}

bool wants_points(const std::set<OutputKind>& outputs) {
  return std::any_of(std::begin(kPointKinds), std::end(kPointKinds),
                     [&](OutputKind kind) { return outputs.contains(kind); });
}

std::string_view word_file_name(const ScanParams& scan) {
  return scan.model == SensorModel::milows ? "flight.d64" : "flight.hellas";
}

}  // namespace owsim
