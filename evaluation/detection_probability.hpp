#pragma once
// Detection probability versus range from ground truth (INTERFACE.md "Ground truth and detection
// evidence"; the definitions in docs/evidence.md):
//  - a *window* is n = max(1, ⌊W / frame period⌋) consecutive frames f … f+n−1 of one flight,
//    every f whose window fits in the flight; it counts in the range bin of the target's range
//    at frame f when the target is in view at f, and is detected when the target's returns over
//    the n frames sum to at least K;
//  - a *trial* is one flight of one target; its detection range D is the target's range at frame
//    f of its first detected window; it counts in a bin when the target was in view at some frame
//    at a range ≥ the bin's lower edge, and is detected there when D ≥ that edge.
// Each proportion with its count and a Clopper–Pearson interval (evaluation/clopper_pearson.hpp).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "evaluation/clopper_pearson.hpp"
#include "evaluation/truth_table.hpp"

namespace owsim {

// At least `returns` returns on the target within a window of `window_s` seconds.
struct DetectionCriterion {
  std::uint64_t returns = 1;
  double window_s = 1.0;
};

// Bins [lo, lo + step), …, up to hi (the last bin ends at hi, possibly narrower). validate()
// bounds them: 0 ≤ lo < hi ≤ kMaxRangeM, kMinBinStepM ≤ step ≤ hi − lo (truth.csv holds ranges to
// the millimetre) and at most kMaxBins bins.
inline constexpr double kMinBinStepM = 0.001;
inline constexpr std::size_t kMaxBins = 100'000;
struct RangeBins {
  double lo_m = 0.0;
  double hi_m = 1300.0;
  double step_m = 50.0;
  [[nodiscard]] std::size_t count() const;
  // The bin of `range_m`, or std::nullopt outside [lo, hi).
  [[nodiscard]] std::optional<std::size_t> bin_of(double range_m) const;
  [[nodiscard]] double bin_lo_m(std::size_t bin) const;
  [[nodiscard]] double bin_hi_m(std::size_t bin) const;
};

// One flight of one target: its truth rows and the flight's facts.
struct TargetFlight {
  std::span<const TruthEntry> rows;  // frame order
  FlightFacts flight;
};

struct PdBin {
  double range_lo_m = 0.0;
  double range_hi_m = 0.0;
  std::uint64_t windows = 0;
  std::uint64_t windows_detected = 0;
  ProportionInterval window_interval;
  std::uint64_t trials = 0;
  std::uint64_t trials_detected = 0;
  ProportionInterval cumulative_interval;
};

// The probabilities pd.json reports the demonstrated range for.
inline constexpr std::array<double, 3> kDemonstratedProbabilities = {0.9, 0.99, 0.995};

struct PdCurve {
  std::vector<PdBin> bins;
  std::uint64_t trials = 0;           // flights in which the target came into view
  std::uint64_t trials_detected = 0;  // of them, those with a detected window
  // By kDemonstratedProbabilities: going outward from the nearest bin with windows, over the
  // bins with windows, range_hi_m of the last bin before the first whose window interval's lower
  // bound is below the probability; nullopt when the first one already is (or none has windows).
  std::array<std::optional<double>, kDemonstratedProbabilities.size()> demonstrated_range_m;
};

// One trial: the farthest range at which the target was in view, and the range at which it was
// first detected (none: never).
struct Trial {
  double farthest_in_view_m = 0.0;
  std::optional<double> detection_range_m;
};

// Adds `trials` to the trial counts of `bins` (made for `ranges`): a trial counts in a bin when
// farthest_in_view_m ≥ its lower edge, and is detected there when detection_range_m ≥ that edge.
void add_trials(std::span<const Trial> trials, std::vector<PdBin>& bins);

// Empty bins over `ranges`.
[[nodiscard]] std::vector<PdBin> empty_bins(const RangeBins& ranges);

// Sets every bin's intervals from its counts.
void set_intervals(std::vector<PdBin>& bins, double confidence);

// The window length in frames: max(1, ⌊W / frame period⌋), at most kMaxFrames + 1 (a window no
// flight holds).
[[nodiscard]] std::int64_t window_frames(double window_s, double frame_period_s);

// The curve over `flights` (every flight of every pooled target; each flight's rows in strictly
// increasing frame order, as read_truth_csv keeps them), in time and memory by the rows and the
// bins, whatever the frames. Throws owsim::Error for a criterion or bins out of range.
[[nodiscard]] PdCurve detection_probability(std::span<const TargetFlight> flights,
                                            const DetectionCriterion& criterion,
                                            const RangeBins& bins, double confidence);

// Checks the criterion, the bins and the confidence; owsim::Error naming the option otherwise.
void validate(const DetectionCriterion& criterion, const RangeBins& bins, double confidence);

}  // namespace owsim
