// Protects the detection statistics (evaluation/clopper_pearson.hpp, detection_probability.hpp):
// Clopper–Pearson bounds pinned to closed forms and published values, the windows needed without a
// miss (736 for 99.5 % at 95 %), and windows, trials, bins and demonstrated ranges counted by hand
// on small tracks; windows summed over the rows, not over the frames they name (a track whose
// frames lie 10¹² apart); --bins refused in one line unless finite, 0 ≤ LO < HI ≤ 1000 km,
// 1 mm ≤ STEP ≤ HI − LO and at most 10⁵ bins (issue 45: 0:1300:1e308 crashed).
#include <gtest/gtest.h>

#include <cmath>

#include "evaluation/detection_probability.hpp"
#include "evaluation/pd_report.hpp"
#include "geometry/error.hpp"

namespace owsim {
namespace {

TEST(ClopperPearson, BoundsWithoutMissesOrHitsAreClosedForms) {
  // k = n: lower = (α/2)^(1/n); k = 0: upper = 1 − (α/2)^(1/n).
  const ProportionInterval all = clopper_pearson(10, 10, 0.95);
  EXPECT_NEAR(all.lower, std::pow(0.025, 0.1), 1e-14);
  EXPECT_EQ(all.upper, 1.0);
  const ProportionInterval none = clopper_pearson(0, 10, 0.95);
  EXPECT_EQ(none.lower, 0.0);
  EXPECT_NEAR(none.upper, 1.0 - std::pow(0.025, 0.1), 1e-14);
}

TEST(ClopperPearson, MatchesPublishedValues) {
  // 5 of 10 at 95 %: (0.187086, 0.812914), as tabulated; the digits are scipy.stats.beta.ppf's.
  const ProportionInterval half = clopper_pearson(5, 10, 0.95);
  EXPECT_NEAR(half.lower, 0.18708602844739, 1e-10);
  EXPECT_NEAR(half.upper, 0.81291397155261, 1e-10);
  // 1 of 20 at 90 % (scipy: beta.ppf(0.05, 1, 20), beta.ppf(0.95, 2, 19)).
  const ProportionInterval rare = clopper_pearson(1, 20, 0.90);
  EXPECT_NEAR(rare.lower, 0.0025613787765302806, 1e-12);
  EXPECT_NEAR(rare.upper, 0.2161061642068473, 1e-12);
  EXPECT_TRUE(std::isnan(clopper_pearson(0, 0, 0.95).lower));
  EXPECT_THROW((void)clopper_pearson(3, 2, 0.95), Error);
  EXPECT_THROW((void)clopper_pearson(1, 2, 1.0), Error);
}

TEST(ClopperPearson, WindowsNeededWithoutMisses) {
  EXPECT_EQ(trials_needed_without_misses(0.995, 0.95), 736u);  // the figure
  EXPECT_EQ(trials_needed_without_misses(0.99, 0.95), 368u);
  EXPECT_EQ(trials_needed_without_misses(0.9, 0.95), 36u);
  for (const double p : {0.9, 0.99, 0.995}) {
    const std::uint64_t n = trials_needed_without_misses(p, 0.95);
    EXPECT_GE(clopper_pearson(n, n, 0.95).lower, p);
    EXPECT_LT(clopper_pearson(n - 1, n - 1, 0.95).lower, p);
  }
}

// frames 0..9 in view, 1000 m at frame 0 closing 50 m a frame; returns at frames 4, 7, 8, 9.
std::vector<TruthEntry> approach() {
  std::vector<TruthEntry> rows;
  const int returns[10] = {0, 0, 0, 0, 1, 0, 0, 1, 1, 1};
  for (int f = 0; f < 10; ++f) {
    TruthEntry row;
    row.frame = f;
    row.range_m = 1000.0 - 50.0 * f;
    row.in_view = true;
    row.returns = static_cast<std::uint64_t>(returns[f]);
    rows.push_back(row);
  }
  return rows;
}

TEST(DetectionProbability, CountsWindowsAndTrialsByHand) {
  const std::vector<TruthEntry> rows = approach();
  const FlightFacts flight{10, 1.0 / 3.0};
  const TargetFlight flights[] = {{rows, flight}};
  const RangeBins bins{600.0, 1100.0, 100.0};
  const PdCurve curve = detection_probability(flights, {1, 1.0}, bins, 0.95);
  ASSERT_EQ(curve.bins.size(), 5u);
  // 3-frame windows start at frames 0..7; those starting at 0 and 1 hold no return, 2..7 do.
  // By range: f0 1000 → bin 4, f1 950 and f2 900 → bin 3, f3 850 and f4 800 → bin 2,
  // f5 750 and f6 700 → bin 1, f7 650 → bin 0.
  const std::uint64_t windows[5] = {1, 2, 2, 2, 1};
  const std::uint64_t detected[5] = {1, 2, 2, 1, 0};
  for (std::size_t b = 0; b < 5; ++b) {
    EXPECT_EQ(curve.bins[b].windows, windows[b]) << b;
    EXPECT_EQ(curve.bins[b].windows_detected, detected[b]) << b;
    // One trial: in view from 1000 m, first detected window at frame 2 (900 m).
    EXPECT_EQ(curve.bins[b].trials, 1u) << b;
    EXPECT_EQ(curve.bins[b].trials_detected, b <= 3 ? 1u : 0u) << b;
  }
  EXPECT_EQ(curve.trials, 1u);
  EXPECT_EQ(curve.trials_detected, 1u);
  // Two returns within the window: frames 7..9 hold three, 6..8 two, 5..7 one.
  const PdCurve two = detection_probability(flights, {2, 1.0}, bins, 0.95);
  EXPECT_EQ(two.bins[0].windows_detected, 1u);  // f7: 3 returns
  EXPECT_EQ(two.bins[1].windows_detected, 1u);  // f6: 2 (frames 6,7,8), f5: 1
  // A longer window: 2 s = 6 frames; windows start at 0..4.
  const PdCurve longer = detection_probability(flights, {1, 2.0}, bins, 0.95);
  std::uint64_t total = 0;
  for (const PdBin& bin : longer.bins) total += bin.windows;
  EXPECT_EQ(total, 5u);
}

TEST(DetectionProbability, DemonstratedRangeGoesOutwardUntilTheLowerBoundFalls) {
  // 800 flights detected in every window nearer than 500 m and never beyond: every level is shown
  // out to 500 m (800 windows a bin without a miss; 99.5 % needs 736).
  std::vector<std::vector<TruthEntry>> tracks(800);
  std::vector<TargetFlight> flights;
  for (auto& rows : tracks) {
    for (int f = 0; f < 12; ++f) {
      TruthEntry row;
      row.frame = f;
      row.range_m = 1150.0 - 100.0 * f;  // 1150 … 50
      row.in_view = true;
      row.returns = row.range_m < 500.0 ? 1 : 0;
      rows.push_back(row);
    }
    flights.push_back({rows, FlightFacts{12, 1.0}});
  }
  const PdCurve curve = detection_probability(flights, {1, 1.0}, {0.0, 1300.0, 100.0}, 0.95);
  ASSERT_TRUE(curve.demonstrated_range_m[0].has_value());
  EXPECT_DOUBLE_EQ(*curve.demonstrated_range_m[0], 500.0);
  EXPECT_DOUBLE_EQ(*curve.demonstrated_range_m[2], 500.0);  // 800 ≥ 736 windows a bin
  // With 700 flights the 99.5 % bound is not reached in any bin: not demonstrated.
  flights.resize(700);
  const PdCurve fewer = detection_probability(flights, {1, 1.0}, {0.0, 1300.0, 100.0}, 0.95);
  EXPECT_TRUE(fewer.demonstrated_range_m[1].has_value());
  EXPECT_FALSE(fewer.demonstrated_range_m[2].has_value());
}

TEST(DetectionProbability, BadCriteriaAreRefusedNamingTheOption) {
  const auto message = [](const DetectionCriterion& c, const RangeBins& b, double confidence) {
    try {
      validate(c, b, confidence);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message({0, 1.0}, {}, 0.95).rfind("--returns", 0), 0u);
  EXPECT_EQ(message({1, 0.0}, {}, 0.95).rfind("--window-s", 0), 0u);
  EXPECT_EQ(message({1, 1.0}, {100, 50, 10}, 0.95).rfind("--bins", 0), 0u);
  EXPECT_EQ(message({1, 1.0}, {}, 1.5).rfind("--confidence", 0), 0u);
  EXPECT_TRUE(message({1, 1.0}, {}, 0.95).empty());
}

TEST(DetectionProbability, WindowsSumTheRowsWhateverFramesTheyName) {
  // 10¹² frames of 1 µs: a 1 s window is 10⁶ frames. A vector by frame would take 8 TB.
  const FlightFacts flight{1'000'000'000'000, 1e-6};
  const auto row = [](std::int64_t frame, double range_m, std::uint64_t returns) {
    TruthEntry entry;
    entry.frame = frame;
    entry.range_m = range_m;
    entry.in_view = true;
    entry.returns = returns;
    return entry;
  };
  const std::vector<TruthEntry> rows = {
      row(0, 950.0, 0),                // its window reaches the next row's return: detected
      row(999'999, 850.0, 1),          // its own return: detected
      row(1'000'000, 810.0, 0),        // none from here to 2·10⁶: missed
      row(500'000'000'000, 750.0, 0),  // missed
      row(999'999'000'000, 650.0, 3),  // its window ends at the flight's end: detected
      row(999'999'999'999, 550.0, 5),  // its window does not fit: no window
  };
  const TargetFlight flights[] = {{rows, flight}};
  const PdCurve curve = detection_probability(flights, {1, 1.0}, {500.0, 1000.0, 100.0}, 0.95);
  ASSERT_EQ(curve.bins.size(), 5u);
  const std::uint64_t windows[5] = {0, 1, 1, 2, 1};
  const std::uint64_t detected[5] = {0, 1, 0, 1, 1};
  for (std::size_t b = 0; b < 5; ++b) {
    EXPECT_EQ(curve.bins[b].windows, windows[b]) << b;
    EXPECT_EQ(curve.bins[b].windows_detected, detected[b]) << b;
    // One trial, in view out to 950 m and detected there.
    EXPECT_EQ(curve.bins[b].trials, 1u) << b;
    EXPECT_EQ(curve.bins[b].trials_detected, 1u) << b;
  }
  // The last window that fits holds the returns of the last row too: 3 + 5.
  const PdCurve eight = detection_probability(flights, {8, 1.0}, {500.0, 1000.0, 100.0}, 0.95);
  EXPECT_EQ(eight.bins[1].windows_detected, 1u);
  EXPECT_EQ(eight.trials_detected, 1u);
  EXPECT_EQ(eight.bins[1].trials_detected, 1u);  // detected at 650 m
  EXPECT_EQ(eight.bins[2].trials_detected, 0u);
  const PdCurve nine = detection_probability(flights, {9, 1.0}, {500.0, 1000.0, 100.0}, 0.95);
  EXPECT_EQ(nine.trials_detected, 0u);
}

std::string bins_error(const std::string& text) {
  try {
    (void)parse_range_bins(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DetectionProbability, BinsAreBoundedAndRefusedInOneLine) {
  const std::string expected =
      "--bins: expected LO:HI:STEP with 0 ≤ LO < HI ≤ 1000000 m, 0.001 m ≤ STEP ≤ HI − LO and at "
      "most 100000 bins, got ";
  EXPECT_EQ(bins_error("0:1300:1e308"), expected + "0:1300:1e+308");
  EXPECT_EQ(bins_error("0:1e308:1"), expected + "0:1e+308:1");
  EXPECT_EQ(bins_error("0:1300:1e13"), expected + "0:1300:1e+13");
  EXPECT_EQ(bins_error("0:1300:1301"), expected + "0:1300:1301");
  EXPECT_EQ(bins_error("0:1300:0"), expected + "0:1300:0");
  EXPECT_EQ(bins_error("0:1300:-50"), expected + "0:1300:-50");
  EXPECT_EQ(bins_error("0:1300:0.0009"), expected + "0:1300:0.0009");
  EXPECT_EQ(bins_error("0:1000001:100"), expected + "0:1000001:100");
  EXPECT_EQ(bins_error("0:1000000:9.99"), expected + "0:1000000:9.99");  // 100,101 bins
  EXPECT_EQ(bins_error("nan:1300:50"), expected + "nan:1300:50");
  EXPECT_EQ(bins_error("0:inf:50"), expected + "0:inf:50");
  EXPECT_EQ(bins_error("-1:1300:50"), expected + "-1:1300:50");
  EXPECT_EQ(bins_error("0:1300"),
            "--bins: expected LO:HI:STEP in metres (e.g. 0:1300:50), got '0:1300'");
  // At the bounds: 10⁵ bins, one bin of the whole span, millimetre bins.
  EXPECT_EQ(parse_range_bins("0:1000000:10").count(), 100'000u);
  const RangeBins one = parse_range_bins("0:1300:1300");
  EXPECT_EQ(one.count(), 1u);
  EXPECT_EQ(one.bin_of(1299.999), std::optional<std::size_t>(0));
  EXPECT_EQ(parse_range_bins("700:800:0.001").count(), 100'000u);
  // Whatever a RangeBins holds, count() and bin_of() stay within bounds (no crash, no UB).
  const RangeBins wide{0.0, 1300.0, 1e308};
  EXPECT_EQ(wide.count(), 1u);
  EXPECT_EQ(wide.bin_of(600.0), std::optional<std::size_t>(0));
  const RangeBins many{0.0, 1e308, 1.0};
  EXPECT_EQ(many.count(), kMaxBins + 1);
  EXPECT_EQ(many.bin_of(1e300), std::optional<std::size_t>(kMaxBins));
}

}  // namespace
}  // namespace owsim
