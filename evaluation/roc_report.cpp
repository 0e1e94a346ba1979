#include "evaluation/roc_report.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string_view>
#include <utility>

#include "evaluation/roc_figure.hpp"
#include "evaluation/warned_frames.hpp"
#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/json_text.hpp"
#include "io/sweep/sweep_table.hpp"
#include "owsim/version.hpp"

namespace owsim {
namespace {

constexpr std::string_view kRocCsvHeader =
    "value,members,windows,windows_detected,pd_window,pd_window_lo,pd_window_hi,pulses,"
    "false_returns,false_returns_per_s";
constexpr int kRateDigits = 12;

// The value as a finite number, when the whole text is one.
std::optional<double> number_of(std::string_view text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// One row per distinct value: numbers pool by value, other text by spelling.
std::vector<RocRow> roc_rows(std::span<const FlightTracks> flights,
                             std::span<const std::string> values, const RocOptions& options,
                             std::span<const WarningTally> warnings) {
  std::vector<std::optional<double>> numbers;
  for (const std::string& value : values) numbers.push_back(number_of(value));
  const bool numeric = std::all_of(numbers.begin(), numbers.end(),
                                   [](const std::optional<double>& n) { return n.has_value(); });
  std::vector<RocRow> rows;
  std::vector<std::vector<std::size_t>> members_of;  // by row
  for (std::size_t m = 0; m < values.size(); ++m) {
    const auto same = [&](const RocRow& row) {
      return numeric ? *row.number == *numbers[m] : row.value == values[m];
    };
    const auto found = std::find_if(rows.begin(), rows.end(), same);
    const auto r = static_cast<std::size_t>(found - rows.begin());
    if (found == rows.end()) {
      RocRow row;
      row.value = values[m];
      row.number = numeric ? numbers[m] : std::nullopt;
      rows.push_back(std::move(row));
      members_of.emplace_back();
    }
    members_of[r].push_back(m);
  }
  const RangeBins bin{options.range_lo_m, options.range_hi_m,
                      options.range_hi_m - options.range_lo_m};
  for (std::size_t r = 0; r < rows.size(); ++r) {
    RocRow& row = rows[r];
    std::vector<TargetFlight> pooled;
    for (const std::size_t m : members_of[r]) {
      const std::vector<TargetFlight> member = target_flights(flights.subspan(m, 1));
      pooled.insert(pooled.end(), member.begin(), member.end());
      row.false_returns += false_returns_of(flights[m].facts);
      if (!warnings.empty()) {
        if (!row.warnings) row.warnings.emplace();
        *row.warnings += warnings[m];
      }
    }
    row.members = members_of[r].size();
    const PdCurve curve = detection_probability(pooled, options.criterion, bin, options.confidence);
    row.windows = curve.bins.front().windows;
    row.windows_detected = curve.bins.front().windows_detected;
    row.window_interval = curve.bins.front().window_interval;
  }
  std::sort(rows.begin(), rows.end(), [numeric](const RocRow& a, const RocRow& b) {
    return numeric ? *a.number < *b.number : a.value < b.value;
  });
  return rows;
}

std::optional<double> pd_of(const RocRow& row) {
  if (row.windows == 0) return std::nullopt;
  return static_cast<double>(row.windows_detected) / static_cast<double>(row.windows);
}

std::string roc_csv(const RocReport& report) {
  std::string out(kRocCsvHeader);
  const bool warnings = !report.rows.empty() && report.rows.front().warnings.has_value();
  if (warnings) out += ",warning_tracks,false_warnings,flight_h,false_warnings_per_h";
  out += '\n';
  for (const RocRow& row : report.rows) {
    out += csv_cell(row.value);
    for (const std::uint64_t count : {row.members, row.windows, row.windows_detected}) {
      out += ',';
      append_csv_integer(out, static_cast<std::int64_t>(count));
    }
    out += ',';
    if (const std::optional<double> pd = pd_of(row)) {
      append_csv_fixed(out, *pd, kProportionDecimals);
    }
    out += ',';
    append_csv_fixed(out, row.window_interval.lower, kProportionDecimals);  // NaN: empty
    out += ',';
    append_csv_fixed(out, row.window_interval.upper, kProportionDecimals);
    for (const std::uint64_t count : {row.false_returns.pulses, row.false_returns.false_returns}) {
      out += ',';
      append_csv_integer(out, static_cast<std::int64_t>(count));
    }
    out += ',';
    append_csv_significant(out, row.false_returns.per_s(), kRateDigits);
    if (row.warnings) {
      for (const std::uint64_t count : {row.warnings->tracks, row.warnings->false_warnings}) {
        out += ',';
        append_csv_integer(out, static_cast<std::int64_t>(count));
      }
      out += ',';
      append_csv_significant(out, row.warnings->hours, kRateDigits);
      out += ',';
      append_csv_significant(out, row.warnings->false_warnings_per_hour(), kRateDigits);
    }
    out += '\n';
  }
  return out;
}

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json roc_json(const RocReport& report, const RocOptions& options) {
  nlohmann::json rows = nlohmann::json::array();
  for (const RocRow& row : report.rows) {
    const std::optional<double> pd = pd_of(row);
    rows.push_back({{"value", row.number ? nlohmann::json(*row.number) : nlohmann::json(row.value)},
                    {"members", row.members},
                    {"windows", row.windows},
                    {"windows_detected", row.windows_detected},
                    {"pd_window", pd ? nlohmann::json(*pd) : nlohmann::json(nullptr)},
                    {"pd_window_lo", number_or_null(row.window_interval.lower)},
                    {"pd_window_hi", number_or_null(row.window_interval.upper)},
                    {"pulses", row.false_returns.pulses},
                    {"false_returns", row.false_returns.false_returns},
                    {"flight_s", row.false_returns.flight_s},
                    {"false_returns_per_s", number_or_null(row.false_returns.per_s())}});
    if (row.warnings) {
      rows.back()["warning_tracks"] = row.warnings->tracks;
      rows.back()["false_warnings"] = row.warnings->false_warnings;
      rows.back()["flight_hours"] = row.warnings->hours;
      rows.back()["false_warnings_per_hour"] = row.warnings->false_warnings_per_hour();
    }
  }
  nlohmann::json out = {{"target", report.target},
          {"by", options.by},
          {"range_m", {options.range_lo_m, options.range_hi_m}},
          {"returns", options.criterion.returns},
          {"window_s", options.criterion.window_s},
          {"confidence", options.confidence},
          {"interval", kIntervalMethod},
          {"flights", report.flights},
          {"rows", rows},
          {"definitions", "docs/evidence.md (owsim " + std::string(version_string) + ")"}};
  if (options.detections) {
    out["evidence"] = "warnings";
    out["gate_m"] = options.gate_m;
  }
  return out;
}

}  // namespace

void parse_roc_range(const std::string& text, RocOptions& options) {
  double lo = 0.0;
  double hi = 0.0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf%c", &lo, &hi, &extra) != 2) {
    throw input_error("--range", "expected LO:HI in metres (e.g. 700:800), got '" + text + "'");
  }
  options.range_lo_m = lo;
  options.range_hi_m = hi;
}

RocReport roc_report_of(std::span<const FlightTracks> members, std::span<const std::string> values,
                        const RocOptions& options, std::span<const WarningTally> warnings) {
  if (values.size() != members.size()) {
    throw Error("roc: " + std::to_string(values.size()) + " values for " +
                std::to_string(members.size()) + " members");
  }
  RocReport report;
  report.target = options.target.name();
  report.flights = members.size();
  if (!warnings.empty() && warnings.size() != members.size()) {
    throw Error("roc: " + std::to_string(warnings.size()) + " warning tallies for " +
                std::to_string(members.size()) + " members");
  }
  report.rows = roc_rows(members, values, options, warnings);
  return report;
}

std::vector<ReportFile> roc_report_files(const RocReport& report, const RocOptions& options) {
  return {{"roc.csv", roc_csv(report)},
          {"roc.json", json_text(roc_json(report, options), 2) + "\n"},
          {"roc.svg", roc_svg(report, options)}};
}

RocReport write_roc_report(const RocOptions& options) {
  if (!(std::isfinite(options.range_lo_m) && std::isfinite(options.range_hi_m) &&
        options.range_lo_m >= 0.0 && options.range_hi_m <= kMaxRangeM &&
        options.range_hi_m - options.range_lo_m >= kMinBinStepM)) {
    throw input_error("--range", "expected 0 ≤ LO < HI ≤ " + number_text(kMaxRangeM, 15) +
                                     " m with HI − LO ≥ " + number_text(kMinBinStepM) + " m, got " +
                                     number_text(options.range_lo_m) + ":" +
                                     number_text(options.range_hi_m));
  }
  validate(options.criterion,
           {options.range_lo_m, options.range_hi_m, options.range_hi_m - options.range_lo_m},
           options.confidence);
  validate(options.target);
  const std::filesystem::path table = options.folder / "sweep.csv";
  std::error_code error;
  if (!std::filesystem::is_regular_file(table, error)) {
    throw input_error(options.folder.string(),
                      "not a sweep folder (no sweep.csv): owsim roc compares the members of an "
                      "owsim sweep");
  }
  const std::vector<CampaignFlight> members = campaign_flights(options.folder);
  const std::vector<std::string> values = read_sweep_values(table, options.by);
  if (values.size() != members.size()) {
    throw input_error(table.string(), "changed while it was read");
  }
  std::vector<FlightTracks> flights;
  for (const CampaignFlight& member : members) {
    flights.push_back(read_target_tracks(member, options.target));
  }
  std::vector<WarningTally> warnings;
  if (options.detections) {
    warnings = count_flights_warnings(options.folder, members, flights, *options.detections,
                                      options.gate_m);
  }
  require_target_found(options.target, flights, options.folder);

  RocReport report = roc_report_of(flights, values, options, warnings);
  report.directory = options.out ? *options.out : options.folder;
  write_report_files(report.directory, roc_report_files(report, options));
  return report;
}

}  // namespace owsim
