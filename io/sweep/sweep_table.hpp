#pragma once
// sweep.csv of `owsim sweep` (INTERFACE.md "Beyond one machine"): one row per member, made from
// the members' summary.json files once all are done, so it is the same whatever process ran which
// member. Columns: member, each varied key (its value as YAML text), frames, pulses,
// returns_wire, returns_pole, returns_tree, returns_ground, second_returns, then for every wire
// in any member (in the order they first appear) first_seen_range_m[<wire id>], metres with 4
// decimals, empty where the member never saw it or has no such wire.
#include <filesystem>

#include "io/sweep/sweep_file.hpp"

namespace owsim {

// `<out>/<member>/summary.json` of every member of `spec` → `<out>/sweep.csv` (written atomically).
// Throws owsim::Error naming the summary that is missing or not an owsim summary.
void write_sweep_table(const SweepSpec& spec, const std::filesystem::path& out);

// `<out>/<member>/`.
[[nodiscard]] std::filesystem::path member_directory(const SweepSpec& spec,
                                                     const std::filesystem::path& out,
                                                     std::int64_t member);

}  // namespace owsim
