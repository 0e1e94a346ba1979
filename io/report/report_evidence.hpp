#pragma once
// The detection evidence a flight folder holds, for the report page's evidence section (`owsim
// view`, docs/evidence.md): `owsim pd`'s pd.json and pd.csv, `owsim roc`'s roc.json and `owsim
// score`'s score.json, when they were written into the folder. pd.csv's bins go to the page as
// numbers; roc.json whole (its rows are one per value of the key); score.json's by-class figures,
// false alarms and confusion table whole, its objects up to a budget.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace owsim {

// {"pd": {...pd.json, "rows": [[lo, hi, windows, detected, pd, lo, hi, trials, detected, pd, lo,
// hi], …]} | null, "roc": {...roc.json} | null, "score": {...score.json, "objects": first
// `max_objects`} | null}; all null when the folder has none. Throws owsim::Error naming the file if
// one is not what owsim wrote.
[[nodiscard]] nlohmann::json report_evidence_json(const std::filesystem::path& folder,
                                                  std::size_t max_objects);

}  // namespace owsim
