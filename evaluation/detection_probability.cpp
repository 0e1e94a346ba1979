#include "evaluation/detection_probability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {

std::size_t RangeBins::count() const {
  // Bins of a step up to hi (a last one shorter than 1e-9 of a step left out); at least one, at
  // most kMaxBins + 1 whatever the values (validate() refuses more than kMaxBins).
  const double bins = std::ceil((hi_m - lo_m) / step_m - 1e-9);
  if (!(bins >= 1.0)) return 1;
  if (bins > static_cast<double>(kMaxBins)) return kMaxBins + 1;
  return static_cast<std::size_t>(bins);
}

std::optional<std::size_t> RangeBins::bin_of(double range_m) const {
  if (!(range_m >= lo_m && range_m < hi_m)) return std::nullopt;
  const double bin = std::floor((range_m - lo_m) / step_m);
  return std::min(static_cast<std::size_t>(std::min(bin, static_cast<double>(kMaxBins))),
                  count() - 1);
}

double RangeBins::bin_lo_m(std::size_t bin) const {
  return lo_m + static_cast<double>(bin) * step_m;
}

double RangeBins::bin_hi_m(std::size_t bin) const {
  return std::min(hi_m, lo_m + static_cast<double>(bin + 1) * step_m);
}

void validate(const DetectionCriterion& criterion, const RangeBins& bins, double confidence) {
  if (criterion.returns < 1) throw input_error("--returns", "must be at least 1");
  if (!(criterion.window_s > 0.0 && criterion.window_s <= 3600.0)) {
    throw input_error("--window-s", "must lie in (0, 3600] s");
  }
  if (!(std::isfinite(bins.lo_m) && std::isfinite(bins.hi_m) && std::isfinite(bins.step_m) &&
        bins.lo_m >= 0.0 && bins.hi_m > bins.lo_m && bins.hi_m <= kMaxRangeM &&
        bins.step_m >= kMinBinStepM && bins.step_m <= bins.hi_m - bins.lo_m &&
        bins.count() <= kMaxBins)) {
    throw input_error(
        "--bins", "expected LO:HI:STEP with 0 ≤ LO < HI ≤ " + number_text(kMaxRangeM, 15) + " m, " +
                      number_text(kMinBinStepM) + " m ≤ STEP ≤ HI − LO and at most " +
                      std::to_string(kMaxBins) + " bins, got " + number_text(bins.lo_m) + ":" +
                      number_text(bins.hi_m) + ":" + number_text(bins.step_m));
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw input_error("--confidence", "must lie between 0 and 1 (e.g. 0.95)");
  }
}

std::int64_t window_frames(double window_s, double frame_period_s) {
  // A window of exactly k frame periods is k frames, despite rounding in the period.
  const double frames = std::floor(window_s / frame_period_s + 1e-9);
  if (!(frames >= 1.0)) return 1;
  return frames > static_cast<double>(kMaxFrames) ? kMaxFrames + 1
                                                  : static_cast<std::int64_t>(frames);
}

std::vector<PdBin> empty_bins(const RangeBins& ranges) {
  std::vector<PdBin> bins(ranges.count());
  for (std::size_t b = 0; b < bins.size(); ++b) {
    bins[b].range_lo_m = ranges.bin_lo_m(b);
    bins[b].range_hi_m = ranges.bin_hi_m(b);
  }
  return bins;
}

void add_trials(std::span<const Trial> trials, std::vector<PdBin>& bins) {
  // A trial counts in the bins whose lower edge it reached: a run of bins from the first, marked
  // at its end and summed from the outermost bin inward.
  std::vector<std::uint64_t> reached(bins.size() + 1, 0);
  std::vector<std::uint64_t> detected(bins.size() + 1, 0);
  const auto bins_up_to = [&](double range_m) {
    return static_cast<std::size_t>(
        std::upper_bound(bins.begin(), bins.end(), range_m,
                         [](double range, const PdBin& bin) { return range < bin.range_lo_m; }) -
        bins.begin());
  };
  for (const Trial& trial : trials) {
    ++reached[bins_up_to(trial.farthest_in_view_m)];
    if (trial.detection_range_m) ++detected[bins_up_to(*trial.detection_range_m)];
  }
  std::uint64_t reached_beyond = 0;
  std::uint64_t detected_beyond = 0;
  for (std::size_t b = bins.size(); b-- > 0;) {
    reached_beyond += reached[b + 1];
    detected_beyond += detected[b + 1];
    bins[b].trials += reached_beyond;
    bins[b].trials_detected += detected_beyond;
  }
}

void set_intervals(std::vector<PdBin>& bins, double confidence) {
  for (PdBin& bin : bins) {
    bin.window_interval = clopper_pearson(bin.windows_detected, bin.windows, confidence);
    bin.cumulative_interval = clopper_pearson(bin.trials_detected, bin.trials, confidence);
  }
}

PdCurve detection_probability(std::span<const TargetFlight> flights,
                              const DetectionCriterion& criterion, const RangeBins& bins,
                              double confidence) {
  validate(criterion, bins, confidence);
  PdCurve curve;
  curve.bins = empty_bins(bins);
  std::vector<Trial> trials;
  std::vector<std::uint64_t> returns_before;  // prefix sums of returns over the flight's rows
  for (const TargetFlight& flight : flights) {
    const std::span<const TruthEntry> rows = flight.rows;
    if (rows.empty()) continue;
    const std::int64_t n = window_frames(criterion.window_s, flight.flight.frame_period_s);
    // returns_before[i] = returns of rows 0 … i − 1: sized by the rows, not by their frames.
    returns_before.assign(rows.size() + 1, 0);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      returns_before[i + 1] = returns_before[i] + rows[i].returns;
    }
    std::size_t window_end = 0;  // the first row at or beyond the current window's end
    double farthest_in_view = -1.0;
    std::optional<double> detection_range;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const TruthEntry& row = rows[i];
      if (!row.in_view) continue;
      farthest_in_view = std::max(farthest_in_view, row.range_m);
      if (row.frame > flight.flight.frames - n) continue;  // the window does not fit
      // A frame without a row has no returns: the window's are those of the rows from this one up
      // to the first at frame f + n or later.
      window_end = std::max(window_end, i);
      while (window_end < rows.size() && rows[window_end].frame - row.frame < n) ++window_end;
      const bool detected = returns_before[window_end] - returns_before[i] >= criterion.returns;
      if (detected && !detection_range) detection_range = row.range_m;
      if (const std::optional<std::size_t> bin = bins.bin_of(row.range_m)) {
        ++curve.bins[*bin].windows;
        if (detected) ++curve.bins[*bin].windows_detected;
      }
    }
    if (farthest_in_view < 0.0) continue;  // never in view: not a trial
    ++curve.trials;
    if (detection_range) ++curve.trials_detected;
    trials.push_back({farthest_in_view, detection_range});
  }
  add_trials(trials, curve.bins);
  set_intervals(curve.bins, confidence);
  for (std::size_t p = 0; p < kDemonstratedProbabilities.size(); ++p) {
    std::optional<double> reached;
    for (const PdBin& bin : curve.bins) {
      if (bin.windows == 0) continue;
      if (bin.window_interval.lower < kDemonstratedProbabilities[p]) break;
      reached = bin.range_hi_m;
    }
    curve.demonstrated_range_m[p] = reached;
  }
  return curve;
}

}  // namespace owsim
