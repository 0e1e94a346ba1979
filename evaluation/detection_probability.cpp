#include "evaluation/detection_probability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/error.hpp"

namespace owsim {
namespace {

constexpr std::size_t kMaxBins = 100'000;

}  // namespace

std::size_t RangeBins::count() const {
  return static_cast<std::size_t>(std::ceil((hi_m - lo_m) / step_m - 1e-9));
}

std::optional<std::size_t> RangeBins::bin_of(double range_m) const {
  if (!(range_m >= lo_m && range_m < hi_m)) return std::nullopt;
  const auto bin = static_cast<std::size_t>(std::floor((range_m - lo_m) / step_m));
  return std::min(bin, count() - 1);
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
  if (!(std::isfinite(bins.lo_m) && std::isfinite(bins.hi_m) && bins.lo_m >= 0.0 &&
        bins.step_m > 0.0 && bins.hi_m > bins.lo_m)) {
    throw input_error("--bins", "expected LO:HI:STEP with 0 ≤ LO < HI and STEP > 0");
  }
  if (bins.count() > kMaxBins) {
    throw input_error("--bins", "more than " + std::to_string(kMaxBins) + " bins");
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw input_error("--confidence", "must lie between 0 and 1 (e.g. 0.95)");
  }
}

std::int64_t window_frames(double window_s, double frame_period_s) {
  // A window of exactly k frame periods is k frames, despite rounding in the period.
  return std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::floor(window_s / frame_period_s + 1e-9)));
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
  for (const Trial& trial : trials) {
    for (PdBin& bin : bins) {
      if (trial.farthest_in_view_m < bin.range_lo_m) continue;
      ++bin.trials;
      if (trial.detection_range_m && *trial.detection_range_m >= bin.range_lo_m) {
        ++bin.trials_detected;
      }
    }
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
  std::vector<std::uint64_t> returns_before;  // prefix sums of returns over the flight's frames
  for (const TargetFlight& flight : flights) {
    if (flight.rows.empty()) continue;
    const std::int64_t n = window_frames(criterion.window_s, flight.flight.frame_period_s);
    const std::int64_t first_frame = flight.rows.front().frame;
    const std::int64_t last_frame = flight.rows.back().frame;
    // returns_before[i] = returns in frames first_frame … first_frame + i − 1.
    returns_before.assign(static_cast<std::size_t>(last_frame - first_frame + 2), 0);
    for (const TruthEntry& row : flight.rows) {
      returns_before[static_cast<std::size_t>(row.frame - first_frame + 1)] = row.returns;
    }
    for (std::size_t i = 1; i < returns_before.size(); ++i) {
      returns_before[i] += returns_before[i - 1];
    }
    const auto returns_in = [&](std::int64_t from, std::int64_t count) {
      const auto at = [&](std::int64_t frame) {
        return returns_before[static_cast<std::size_t>(
            std::clamp(frame, first_frame, last_frame + 1) - first_frame)];
      };
      return at(from + count) - at(from);
    };

    double farthest_in_view = -1.0;
    std::optional<double> detection_range;
    for (const TruthEntry& row : flight.rows) {
      if (!row.in_view) continue;
      farthest_in_view = std::max(farthest_in_view, row.range_m);
      if (row.frame + n > flight.flight.frames) continue;  // the window does not fit
      const bool detected = returns_in(row.frame, n) >= criterion.returns;
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
