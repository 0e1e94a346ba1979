#pragma once
// summary.json read back for `owsim view`, streamed: the run's facts whole, and of its `objects`
// (one a scenario object: a million-tree forest writes ~200 MB) only the ground-truth rows the page
// lists — the first max_objects by first-seen time (objects never seen after, in file order) —
// so memory stays ~1 KB per row kept, not per object in the file.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace owsim {

struct ReportSummary {
  nlohmann::json facts;    // every key but "objects"
  nlohmann::json objects;  // the rows kept, first seen first
  std::size_t objects_total = 0;
};

// Throws owsim::FileError if the file cannot be read, owsim::Error naming it if it is not a JSON
// object.
[[nodiscard]] ReportSummary read_report_summary(const std::filesystem::path& path,
                                                std::size_t max_objects);

}  // namespace owsim
