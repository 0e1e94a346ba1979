#pragma once
// `owsim pd` (INTERFACE.md "Ground truth and detection evidence"): detection probability versus
// range over a run or sweep folder's truth.csv files, written as pd.csv, pd.json and pd.svg
// (curves with their Clopper–Pearson bands); pd.json also gives the sensor's false returns over
// the flights read (false_returns, pulses, false_returns_per_s: evaluation/false_returns.hpp). The
// three files are rendered in memory and replaced together (evaluation/report_files.hpp).
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "evaluation/detection_probability.hpp"
#include "evaluation/false_returns.hpp"
#include "evaluation/pd_target.hpp"
#include "evaluation/report_files.hpp"

namespace owsim {

struct PdOptions {
  std::filesystem::path folder;          // a run folder or a sweep folder
  std::optional<std::string> target_id;  // one object, by id
  std::string target_class = "wire";     // else every object of this class, pooled
  DetectionCriterion criterion;
  RangeBins bins;
  double confidence = 0.95;
  std::optional<std::filesystem::path> out;  // default: `folder`
};

struct PdReport {
  std::string target;  // the id, or "class:<class>"
  std::filesystem::path directory;
  std::size_t flights = 0;
  PdCurve curve;
  FalseReturns false_returns;  // the sensor's, summed over the flights' summary.json
};

// Reads the folder's flights, computes the curve and writes the three files. Throws owsim::Error
// naming the file, line or option for bad input (nothing is written then).
[[nodiscard]] PdReport write_pd_report(const PdOptions& options);

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
