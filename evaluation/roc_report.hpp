#pragma once
// `owsim roc` (INTERFACE.md "Receiver noise and sunlight", docs/evidence.md "owsim roc"): over a
// sweep folder whose members differ in one key (default sensor.threshold), per value of the key,
// Pd within W of the target in one range bin [LO, HI) — its windows counted exactly as `owsim pd`
// counts them (detection_probability) — with its Clopper–Pearson interval, against the sensor's
// false returns per second (false_returns.hpp). Written as roc.csv, roc.json and roc.svg, rendered
// in memory after every input has been read and replaced together (report_files.hpp).
// With `detections` (--detections), Pd is the warnings' (evaluation/warned_frames.hpp) and each
// value's false warnings per flight hour are the x axis instead of the false returns.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "evaluation/detection_probability.hpp"
#include "evaluation/false_returns.hpp"
#include "evaluation/warned_frames.hpp"
#include "evaluation/pd_target.hpp"
#include "evaluation/report_files.hpp"

namespace owsim {

struct RocOptions {
  std::filesystem::path folder;  // a sweep folder
  PdTarget target;
  std::string by = "sensor.threshold";  // the varied key whose values make the rows
  double range_lo_m = 700.0;            // the range bin [lo, hi) of the windows' first frame
  double range_hi_m = 800.0;
  DetectionCriterion criterion;
  double confidence = 0.95;
  std::optional<std::filesystem::path> out;  // default: `folder`
  // Warnings instead of returns (as PdOptions::detections): a folder of <member>.csv, or the sweep
  // folder itself.
  std::optional<std::filesystem::path> detections;
  double gate_m = 5.0;
};

// One value of the key: its members pooled.
struct RocRow {
  std::string value;             // as sweep.csv holds it (the first member's spelling, for numbers)
  std::optional<double> number;  // the value, when every value of the sweep is a number
  std::uint64_t members = 0;
  std::uint64_t windows = 0;
  std::uint64_t windows_detected = 0;
  ProportionInterval window_interval;  // NaN bounds without windows
  FalseReturns false_returns;          // summed over the members
  std::optional<WarningTally> warnings;  // with --detections, summed over the members
};

struct RocReport {
  std::string target;  // the id, or "class:<class>"
  std::filesystem::path directory;
  std::size_t flights = 0;
  std::vector<RocRow> rows;  // by value: numerically when every value is a number, else as text
};

// Reads the sweep, computes the rows and writes the three files. Throws owsim::Error naming the
// file, line, key or option for bad input (nothing is written then).
[[nodiscard]] RocReport write_roc_report(const RocOptions& options);

// The report over the members already read (read_target_tracks, evaluation/pd_target.hpp), with
// `values[m]` member m's value of the key, and with --detections `warnings[m]` its warnings (their
// rows already counting warned frames; empty without); `directory` left empty.
[[nodiscard]] RocReport roc_report_of(std::span<const FlightTracks> members,
                                      std::span<const std::string> values,
                                      const RocOptions& options,
                                      std::span<const WarningTally> warnings = {});

// roc.csv, roc.json and roc.svg of `report`, as text.
[[nodiscard]] std::vector<ReportFile> roc_report_files(const RocReport& report,
                                                       const RocOptions& options);

// "LO:HI" (metres) → options.range_lo_m, range_hi_m; owsim::Error naming --range when it is not
// two numbers (write_roc_report checks 0 ≤ LO < HI ≤ kMaxRangeM and HI − LO ≥ kMinBinStepM).
void parse_roc_range(const std::string& text, RocOptions& options);

}  // namespace owsim
