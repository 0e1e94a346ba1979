#include "evaluation/pd_report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "evaluation/pd_target.hpp"
#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/json_text.hpp"
#include "owsim/version.hpp"

namespace owsim {
namespace {

constexpr std::string_view kPdCsvHeader =
    "target,range_lo_m,range_hi_m,windows,windows_detected,pd_window,pd_window_lo,pd_window_hi,"
    "trials,trials_detected,pd_cumulative,pd_cumulative_lo,pd_cumulative_hi";

void append_proportion(std::string& out, std::uint64_t hits, std::uint64_t count,
                       const ProportionInterval& interval) {
  out += ',';
  append_csv_integer(out, static_cast<std::int64_t>(count));
  out += ',';
  append_csv_integer(out, static_cast<std::int64_t>(hits));
  out += ',';
  if (count > 0) {
    append_csv_fixed(out, static_cast<double>(hits) / static_cast<double>(count),
                     kProportionDecimals);
  }
  out += ',';
  append_csv_fixed(out, interval.lower, kProportionDecimals);  // NaN (no count): empty
  out += ',';
  append_csv_fixed(out, interval.upper, kProportionDecimals);
}

std::string pd_csv(const std::string& target, const PdCurve& curve) {
  std::string out(kPdCsvHeader);
  out += '\n';
  for (const PdBin& bin : curve.bins) {
    out += csv_cell(target);
    out += ',';
    append_csv_fixed(out, bin.range_lo_m, 3);
    out += ',';
    append_csv_fixed(out, bin.range_hi_m, 3);
    append_proportion(out, bin.windows_detected, bin.windows, bin.window_interval);
    append_proportion(out, bin.trials_detected, bin.trials, bin.cumulative_interval);
    out += '\n';
  }
  return out;
}

std::string probability_key(double probability) {
  char text[16];
  std::snprintf(text, sizeof text, "%g", probability);
  return text;
}

nlohmann::json pd_json(const PdReport& report, const PdOptions& options) {
  nlohmann::json demonstrated = nlohmann::json::object();
  nlohmann::json needed = nlohmann::json::object();
  for (std::size_t p = 0; p < kDemonstratedProbabilities.size(); ++p) {
    const std::string key = probability_key(kDemonstratedProbabilities[p]);
    const std::optional<double>& range = report.curve.demonstrated_range_m[p];
    demonstrated[key] = range ? nlohmann::json(*range) : nlohmann::json(nullptr);
    needed[key] = trials_needed_without_misses(kDemonstratedProbabilities[p], options.confidence);
  }
  std::uint64_t windows = 0;
  std::uint64_t detected = 0;
  for (const PdBin& bin : report.curve.bins) {
    windows += bin.windows;
    detected += bin.windows_detected;
  }
  return {
      {"target", report.target},
      {"returns", options.criterion.returns},
      {"window_s", options.criterion.window_s},
      {"confidence", options.confidence},
      {"interval", kIntervalMethod},
      {"flights", report.flights},
      {"trials", report.curve.trials},
      {"trials_detected", report.curve.trials_detected},
      {"windows", windows},
      {"windows_detected", detected},
      {"pulses", report.false_returns.pulses},
      {"false_returns", report.false_returns.false_returns},
      {"false_returns_per_s", report.false_returns.per_s()},
      {"bins",
       {{"lo_m", options.bins.lo_m}, {"hi_m", options.bins.hi_m}, {"step_m", options.bins.step_m}}},
      {"demonstrated_range_m", demonstrated},
      // Windows in a bin, none missed, for its interval's lower bound to reach p.
      {"windows_needed_without_misses", needed},
      {"definitions", "docs/evidence.md (owsim " + std::string(version_string) + ")"}};
}

nlohmann::json pd_json_with_warnings(const PdReport& report, const PdOptions& options) {
  nlohmann::json out = pd_json(report, options);
  if (!report.warnings) return out;
  const WarningTally& tally = *report.warnings;
  out["evidence"] = "warnings";
  out["gate_m"] = options.gate_m;
  out["warning_rows"] = tally.rows;
  out["warning_tracks"] = tally.tracks;
  out["false_warnings"] = tally.false_warnings;
  out["flight_hours"] = tally.hours;
  out["false_warnings_per_hour"] = tally.false_warnings_per_hour();
  return out;
}

// The curves with their bands: x range, y probability.
std::string pd_svg(const PdReport& report, const PdOptions& options) {
  constexpr double kWidth = 760, kHeight = 480, kLeft = 70, kRight = 20, kTop = 50, kBottom = 100;
  const double plot_w = kWidth - kLeft - kRight;
  const double plot_h = kHeight - kTop - kBottom;
  const double x0 = options.bins.lo_m;
  const double x1 = options.bins.hi_m;
  const auto x_of = [&](double range) { return kLeft + (range - x0) / (x1 - x0) * plot_w; };
  const auto y_of = [&](double p) { return kTop + (1.0 - p) * plot_h; };
  std::string svg;
  const auto add = [&](const char* format, auto... values) {
    char text[512];
    std::snprintf(text, sizeof text, format, values...);
    svg += text;
  };
  add("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
      "viewBox=\"0 0 %g %g\" font-family=\"sans-serif\" font-size=\"12\">\n",
      kWidth, kHeight, kWidth, kHeight);
  add("<rect width=\"%g\" height=\"%g\" fill=\"white\"/>\n", kWidth, kHeight);
  std::string title = std::string(report.warnings ? "P(warn) of " : "P(detect) of ") +
                      report.target + ": ≥ " + std::to_string(options.criterion.returns) +
                      (report.warnings ? " warned frame(s) within " : " return(s) within ") +
                      probability_key(options.criterion.window_s) + " s, " +
                      probability_key(options.confidence * 100.0) + " % Clopper–Pearson bands";
  std::string escaped;
  for (const char c : title) {
    if (c == '<')
      escaped += "&lt;";
    else if (c == '>')
      escaped += "&gt;";
    else if (c == '&')
      escaped += "&amp;";
    else
      escaped += c;
  }
  svg += "<text x=\"" + std::to_string(kLeft) + "\" y=\"24\" font-size=\"14\">" + escaped +
         "</text>\n";
  for (int tick = 0; tick <= 10; ++tick) {
    const double p = tick / 10.0;
    add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>\n", kLeft, y_of(p),
        kLeft + plot_w, y_of(p));
    add("<text x=\"%g\" y=\"%g\" text-anchor=\"end\">%.1f</text>\n", kLeft - 6, y_of(p) + 4, p);
  }
  const double span = x1 - x0;
  const double raw_step = span / 8.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw_step)));
  double step = magnitude;
  for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
    if (magnitude * factor >= raw_step) {
      step = magnitude * factor;
      break;
    }
  }
  for (double x = std::ceil(x0 / step) * step; x <= x1 + 1e-9; x += step) {
    add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>\n", x_of(x), kTop, x_of(x),
        kTop + plot_h);
    add("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%g</text>\n", x_of(x), kTop + plot_h + 18,
        x);
  }
  add("<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"#444\"/>\n", kLeft,
      kTop, plot_w, plot_h);
  add("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">range (m)</text>\n", kLeft + plot_w / 2,
      kTop + plot_h + 36);
  add("<text transform=\"translate(18 %g) rotate(-90)\" text-anchor=\"middle\">probability of "
      "detection</text>\n",
      kTop + plot_h / 2);
  // A curve through the bins' centres that have counts, its band as a polygon.
  const auto curve = [&](bool windows, const char* colour, const char* label, int legend_row) {
    std::vector<std::array<double, 4>> points;  // x, p, lower, upper
    for (const PdBin& bin : report.curve.bins) {
      const std::uint64_t count = windows ? bin.windows : bin.trials;
      if (count == 0) continue;
      const std::uint64_t hits = windows ? bin.windows_detected : bin.trials_detected;
      const ProportionInterval& ci = windows ? bin.window_interval : bin.cumulative_interval;
      points.push_back({x_of(0.5 * (bin.range_lo_m + bin.range_hi_m)),
                        static_cast<double>(hits) / static_cast<double>(count), ci.lower,
                        ci.upper});
    }
    if (!points.empty()) {
      svg += "<polygon fill=\"" + std::string(colour) + "\" fill-opacity=\"0.2\" points=\"";
      for (const auto& point : points) add("%.2f,%.2f ", point[0], y_of(point[3]));
      for (auto it = points.rbegin(); it != points.rend(); ++it) {
        add("%.2f,%.2f ", (*it)[0], y_of((*it)[2]));
      }
      svg += "\"/>\n<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" + std::string(colour) +
             "\" points=\"";
      for (const auto& point : points) add("%.2f,%.2f ", point[0], y_of(point[1]));
      svg += "\"/>\n";
      for (const auto& point : points) {
        add("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.5\" fill=\"%s\"/>\n", point[0], y_of(point[1]),
            colour);
      }
    }
    const double y = kTop + plot_h + 60 + 16.0 * legend_row;  // the legend under the plot
    add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"%s\" stroke-width=\"2\"/>\n",
        kLeft + 10, y - 4, kLeft + 30, y - 4, colour);
    add("<text x=\"%g\" y=\"%g\">%s</text>\n", kLeft + 36, y, label);
  };
  curve(true, "#1f5fbf", "Pd within the window (per window)", 0);
  curve(false, "#d9730d", "cumulative Pd (per trial, detected at or beyond the range)", 1);
  svg += "</svg>\n";
  return svg;
}

}  // namespace

RangeBins parse_range_bins(const std::string& text) {
  RangeBins bins;
  double values[3];
  char extra = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf:%lf%c", &values[0], &values[1], &values[2], &extra) != 3) {
    throw input_error("--bins",
                      "expected LO:HI:STEP in metres (e.g. 0:1300:50), got '" + text + "'");
  }
  bins.lo_m = values[0];
  bins.hi_m = values[1];
  bins.step_m = values[2];
  validate(DetectionCriterion{}, bins, 0.95);
  return bins;
}

PdReport pd_report_of(std::span<const FlightTracks> flights, const PdOptions& options) {
  PdReport report;
  report.target = PdTarget{options.target_id, options.target_class}.name();
  report.flights = flights.size();
  for (const FlightTracks& flight : flights) report.false_returns += false_returns_of(flight.facts);
  report.curve = detection_probability(target_flights(flights), options.criterion, options.bins,
                                       options.confidence);
  return report;
}

std::vector<ReportFile> pd_report_files(const PdReport& report, const PdOptions& options) {
  return {{"pd.csv", pd_csv(report.target, report.curve)},
          {"pd.json", json_text(pd_json_with_warnings(report, options), 2) + "\n"},
          {"pd.svg", pd_svg(report, options)}};
}

std::vector<FlightTracks> read_pd_flights(const PdOptions& options,
                                          std::optional<WarningTally>& tally) {
  validate(options.criterion, options.bins, options.confidence);
  const PdTarget target{options.target_id, options.target_class};
  validate(target);
  const std::vector<CampaignFlight> flights = campaign_flights(options.folder);
  // Every flight's tracks are kept until the curve is made: a target's rows are a few per frame.
  std::vector<FlightTracks> tracks;
  for (const CampaignFlight& flight : flights) tracks.push_back(read_target_tracks(flight, target));
  if (options.detections) {
    tally.emplace();
    for (const WarningTally& flight : count_flights_warnings(options.folder, flights, tracks,
                                                             *options.detections, options.gate_m)) {
      *tally += flight;
    }
  }
  require_target_found(target, tracks, options.folder);
  return tracks;
}

PdReport write_pd_report(const PdOptions& options) {
  std::optional<WarningTally> tally;
  const std::vector<FlightTracks> tracks = read_pd_flights(options, tally);
  PdReport report = pd_report_of(tracks, options);
  report.warnings = tally;
  report.directory = options.out ? *options.out : options.folder;
  write_report_files(report.directory, pd_report_files(report, options));
  return report;
}

}  // namespace owsim
