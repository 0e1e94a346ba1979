#pragma once
// The physical range of every number a scenario file may hold: one table, checked where the
// loader reads each value (io/scenario/yaml_reader.hpp: "<file>:<line>: <key>: must be in
// [min, max] <unit>, got <value>") and by validate_scenario for scenarios built in code. The
// ranges are wide enough for any real helicopter, sensor and corridor and narrow enough that
// nothing downstream overflows, runs away in memory or time, or leaves Embree's float precision
// (positions within ±200 km of the origin keep 16 mm). docs/scenario.md "Allowed ranges" lists
// the same table; tests/test_value_ranges.cpp holds the two equal.
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace owsim {

struct ValueRange {
  // The file's key path with list indices as [] ("scene.poles[].height_m"); "<position>.e" (.n,
  // .u, .lat, .lon, .h) is a coordinate of any position other than the origin.
  std::string_view key;
  double min;
  double max;
  std::string_view unit;  // "m", "deg", "" …
};

// The largest distance from the scenario origin owsim simulates, metres (Embree's coordinates
// are floats relative to the origin).
inline constexpr double kMaxOffsetFromOriginM = 200'000.0;

// Every row, in the order of docs/scenario.md.
[[nodiscard]] std::span<const ValueRange> value_ranges();

// The row for a key path with or without list indices ("scene.poles[3].height_m"), if any.
[[nodiscard]] const ValueRange* value_range_of(std::string_view key_path);

// "" when value lies in the range of key_path (or key_path has none); else the problem,
// "must be in [0.001, 0.2] m, got 1e+308".
[[nodiscard]] std::string out_of_range_problem(std::string_view key_path, double value);

// The key path with every list index replaced by "[]".
[[nodiscard]] std::string key_pattern(std::string_view key_path);

}  // namespace owsim
