#include "io/run/output_kind.hpp"

#include <algorithm>
#include <utility>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr std::pair<OutputKind, std::string_view> kNames[] = {{OutputKind::d64, "d64"},
                                                              {OutputKind::points, "points"},
                                                              {OutputKind::trajectory, "trajectory"},
                                                              {OutputKind::summary, "summary"},
                                                              {OutputKind::quicklook, "quicklook"}};

}  // namespace

std::set<OutputKind> all_outputs() {
  std::set<OutputKind> kinds;
  for (const auto& [kind, name] : kNames) kinds.insert(kind);
  return kinds;
}

std::set<OutputKind> parse_output_list(std::string_view list) {
  std::set<OutputKind> kinds;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string_view item = list.substr(begin, comma - begin);
    const auto* known = std::find_if(std::begin(kNames), std::end(kNames),
                                     [&](const auto& entry) { return entry.second == item; });
    if (known == std::end(kNames)) {
      throw input_error("--outputs",
                        "unknown output '" + std::string(item) +
                            "' (expected d64, points, trajectory, summary, quicklook)");
    }
    kinds.insert(known->first);
    begin = comma + 1;
  }
  return kinds;
}

std::string output_list(const std::set<OutputKind>& outputs) {
  std::string list;
  for (const auto& [kind, name] : kNames) {
    if (!outputs.contains(kind)) continue;
    if (!list.empty()) list += ',';
    list += name;
  }
  return list;
}

std::string_view word_file_name(const ScanParams& scan) {
  return scan.model == SensorModel::milows ? "flight.d64" : "flight.hellas";
}

}  // namespace owsim
