#pragma once
// sweep.csv of `owsim sweep` (INTERFACE.md "Beyond one machine"): one row per member, made from
// the members' summary.json files once all are done, so it is the same whatever process ran which
// member. Columns: member, each varied key (its value as YAML text), frames, pulses,
// returns_wire, returns_pole, returns_tree, returns_ground, returns_building, returns_fog (where a
// member flew in weather), returns_noise (false returns, SENSOR-SPEC §11; 0 for a member summary
// without them), second_returns, then for every wire
// in any member (in the order they first appear) first_seen_range_m[<wire id>], metres with 4
// decimals, empty where the member never saw it or has no such wire.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/sweep/sweep_file.hpp"

namespace owsim {

// `<out>/<member>/summary.json` of every member of `spec` → `<out>/sweep.csv` (written atomically).
// Throws owsim::Error naming the summary that is missing or not an owsim summary.
void write_sweep_table(const SweepSpec& spec, const std::filesystem::path& out);

// The varied key `key`'s value in each member row of sweep.csv, in row order (the order
// campaign_flights, evaluation/truth_table.hpp, lists the members in), as the YAML text the table
// holds. The varied keys are the header's columns between `member` and `frames,pulses`. Throws
// owsim::Error "<sweep.csv>: <key>: …" when the sweep does not vary `key`, naming the line of a row
// short of cells, or the file when it is not an owsim sweep table.
[[nodiscard]] std::vector<std::string> read_sweep_values(const std::filesystem::path& sweep_csv,
                                                         std::string_view key);

// `<out>/<member>/`.
[[nodiscard]] std::filesystem::path member_directory(const SweepSpec& spec,
                                                     const std::filesystem::path& out,
                                                     std::int64_t member);

}  // namespace owsim
