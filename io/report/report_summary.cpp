#include "io/report/report_summary.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <limits>
#include <tuple>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {
namespace {

using nlohmann::json;

struct Row {
  double first_seen_s;  // +inf: never seen
  std::size_t order;    // in the file
  json object;
};

bool earlier(const Row& a, const Row& b) {
  return std::tie(a.first_seen_s, a.order) < std::tie(b.first_seen_s, b.order);
}

double first_seen(const json& object) {
  const auto it = object.find("first_seen_s");
  return it != object.end() && it->is_number() ? it->get<double>()
                                               : std::numeric_limits<double>::infinity();
}

}  // namespace

ReportSummary read_report_summary(const std::filesystem::path& path, std::size_t max_objects) {
  std::ifstream in(path);
  if (!in) throw file_error(path.string(), "cannot open for reading");
  ReportSummary out;
  std::vector<Row> kept;  // a max-heap by `earlier`: its top is the row to drop next
  bool in_objects = false;
  // Each element of "objects" is judged when it closes and dropped from the tree.
  const json::parser_callback_t keep = [&](int depth, json::parse_event_t event, json& parsed) {
    if (depth == 1 && event == json::parse_event_t::key) {
      in_objects = parsed == "objects";
      return true;
    }
    if (in_objects && depth == 2 && event == json::parse_event_t::object_end) {
      Row row{first_seen(parsed), out.objects_total++, std::move(parsed)};
      if (kept.size() < max_objects) {
        kept.push_back(std::move(row));
        std::push_heap(kept.begin(), kept.end(), earlier);
      } else if (!kept.empty() && earlier(row, kept.front())) {
        std::pop_heap(kept.begin(), kept.end(), earlier);
        kept.back() = std::move(row);
        std::push_heap(kept.begin(), kept.end(), earlier);
      }
      return false;
    }
    return true;
  };
  try {
    out.facts = json::parse(in, keep);
  } catch (const json::exception& e) {
    throw input_error(path.string(), std::string("not JSON: ") + e.what());
  }
  if (!out.facts.is_object()) throw input_error(path.string(), "not a JSON object");
  out.facts.erase("objects");
  std::sort(kept.begin(), kept.end(), earlier);
  out.objects = json::array();
  for (Row& row : kept) out.objects.push_back(std::move(row.object));
  return out;
}

}  // namespace owsim
