#pragma once
// `owsim pd` (INTERFACE.md "Ground truth and detection evidence"): detection probability versus
// range over a run or sweep folder's truth.csv files, written as pd.csv, pd.json and pd.svg
// (curves with their Clopper–Pearson bands); pd.json also gives the sensor's false returns over
// the flights read (false_returns, pulses, false_returns_per_s: evaluation/false_returns.hpp). The
// three files are rendered in memory and replaced together (evaluation/report_files.hpp).
// With `detections` (--detections), the evidence is the detector's warnings instead of the returns
// (evaluation/warned_frames.hpp): a window is detected when at least K of its frames warned of the
// target with its class, and pd.json adds the false warnings per flight hour.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "evaluation/detection_probability.hpp"
#include "evaluation/false_returns.hpp"
#include "evaluation/pd_target.hpp"
#include "evaluation/report_files.hpp"
#include "evaluation/warned_frames.hpp"

namespace owsim {

struct PdOptions {
  std::filesystem::path folder;          // a run folder or a sweep folder
  std::optional<std::string> target_id;  // one object, by id
  std::string target_class = "wire";     // else every object of this class, pooled
  DetectionCriterion criterion;
  RangeBins bins;
  double confidence = 0.95;
  std::optional<std::filesystem::path> out;  // default: `folder`
  // Warnings instead of returns: a detections file (run), a folder of <member>.csv (sweep), or the
  // run or sweep folder itself (detections.csv that output `detections` wrote).
  std::optional<std::filesystem::path> detections;
  double gate_m = 5.0;  // a warning within this of an object's surface hit it
};


struct PdReport {
  std::string target;  // the id, or "class:<class>"
  std::filesystem::path directory;
  std::size_t flights = 0;
  PdCurve curve;
  FalseReturns false_returns;  // the sensor's, summed over the flights' summary.json
  std::optional<WarningTally> warnings;  // with --detections
};

// Reads the folder's flights, computes the curve and writes the three files. Throws owsim::Error
// naming the file, line or option for bad input (nothing is written then).
[[nodiscard]] PdReport write_pd_report(const PdOptions& options);

// The flights of `options.folder` with the target's tracks, their rows counting warned frames when
// `options.detections` is set (`tally` then told the warnings). Throws owsim::Error.
[[nodiscard]] std::vector<FlightTracks> read_pd_flights(const PdOptions& options,
                                                        std::optional<WarningTally>& tally);

// The report over flights already read (read_target_tracks, evaluation/pd_target.hpp): the curve
// and the false returns; `directory` left empty.
[[nodiscard]] PdReport pd_report_of(std::span<const FlightTracks> flights,
                                    const PdOptions& options);

// pd.csv, pd.json and pd.svg of `report`, as text.
[[nodiscard]] std::vector<ReportFile> pd_report_files(const PdReport& report,
                                                      const PdOptions& options);

// "LO:HI:STEP" → RangeBins; owsim::Error naming --bins otherwise.
[[nodiscard]] RangeBins parse_range_bins(const std::string& text);

}  // namespace owsim
