#pragma once
// The sweep file of `owsim sweep` (INTERFACE.md "Beyond one machine"): a campaign of `count`
// scenarios, member m being the base scenario with each key under `vary` set to member m's value:
//
//   base: corridor.yaml        the base scenario, relative to the sweep file
//   count: 200                 members 0..count−1
//   seed: 7                    member m's draws are keyed by (seed, m, key)
//   outputs: d64,summary       as `owsim run --outputs` (default d64,summary,truth; summary.json
//                              is always written: sweep.csv is made from it)
//   vary:                      key path in the base scenario → how it varies
//     scene.spans[0].conductor.diameter_mm: {uniform: [5, 30]}    a ≤ x < b
//     sensor.mount.pitch_deg: {normal: [-4, 1]}                    mean, standard deviation
//     trajectory.waypoints.speed_mps: {choice: [30, 40, 50]}      one item, drawn
//     sensor.model: {values: [milows, hellas]}                     item m mod n, in turn
//     seed: {member: true}                                         the member index itself
//
// A key path is dot-separated map keys with [i] list indices; every key but the last must be in
// the base scenario (the last may be new, e.g. `seed`). Draws are Philox
// (geometry/keyed_random.hpp) keyed by the sweep seed, the member and an FNV-1a hash of the key
// path, so member m's values do not depend on how many members there are, on which process runs it,
// or on the other keys. Errors throw owsim::Error "<file>:<line>: <key>: <problem>".
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace owsim {

struct SweepVariation {
  enum class Kind { uniform, normal, choice, values, member };
  std::string key;  // key path in the base scenario
  Kind kind = Kind::member;
  double a = 0.0;                  // uniform: lower bound; normal: mean
  double b = 0.0;                  // uniform: upper bound; normal: standard deviation
  std::vector<std::string> items;  // choice, values: each item as YAML text (flow style)
  int line = 0;                    // of the key in the sweep file
};

struct SweepSpec {
  std::filesystem::path file;  // the sweep file
  std::string text;            // its contents
  std::filesystem::path base;  // the base scenario (resolved against the sweep file's folder)
  std::string base_text;
  std::int64_t count = 0;
  std::uint64_t seed = 0;
  std::string outputs = "d64,summary,truth";
  std::vector<SweepVariation> vary;  // in file order
};

// Reads and checks a sweep file and its base scenario's text: a base that is not the sweep file
// itself, key paths whose indices fit and that lead through the base (as member 0 has it).
[[nodiscard]] SweepSpec read_sweep_file(const std::filesystem::path& path);

// Member m's value of each variation, in spec.vary order, as YAML text (numbers in their
// shortest round-trip form).
[[nodiscard]] std::vector<std::string> member_values(const SweepSpec& spec, std::int64_t member);

// The base scenario's YAML with member m's values set. Throws owsim::Error naming the sweep file,
// the line and the key if a key path does not lead through the base scenario.
[[nodiscard]] std::string member_scenario_text(const SweepSpec& spec, std::int64_t member);

// "0042": member m's folder name, zero-padded to the digits of count − 1.
[[nodiscard]] std::string member_folder_name(const SweepSpec& spec, std::int64_t member);
// The same for a sweep of `count` members.
[[nodiscard]] std::string member_folder_name(std::int64_t count, std::int64_t member);

}  // namespace owsim
