// Protects the circle–strip footprint (SENSOR-SPEC §7 Decision, eq 7.8–7.10): the exact area
// against scipy's 2-D quadrature, and its reduction to the source's two cases.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "python_oracle.hpp"
#include "sensor/footprint.hpp"

namespace owsim {
namespace {

constexpr double kPi = std::numbers::pi;

struct StripCase {
  double d, w, r;
};

// A dozen geometries: central, offset, partly off an edge, fully off, negative d, wider than
// the disc, covering past one side, mm-wide wire in a km-range beam.
const std::vector<StripCase> kCases = {
    {0.0, 0.01, 0.25},  {0.1, 0.01, 0.25}, {0.245, 0.01, 0.25}, {0.3, 0.01, 0.25},
    {-0.1, 0.01, 0.25}, {0.0, 0.5, 0.25},  {0.3, 0.2, 0.25},    {-0.3, 0.2, 0.25},
    {0.05, 0.1, 0.25},  {0.2, 0.1, 0.25},  {0.0, 0.0025, 0.5},  {1.0, 0.3, 0.5},
    {0.5, 0.25, 1.0},   {0.7, 0.3, 0.5},   {-0.62, 0.15, 0.5},  {0.12, 0.02, 0.1}};

// scipy.integrate.dblquad of 1 over {|x − d| ≤ w, x² + y² ≤ R²}, one line per case.
std::vector<double> scipy_overlaps() {
  std::ostringstream script;
  script << "import math\nfrom scipy.integrate import dblquad\ncases=[";
  script.precision(17);
  for (const auto& c : kCases) script << "(" << c.d << "," << c.w << "," << c.r << "),";
  script << "]\n"
            "for d,w,R in cases:\n"
            "  lo,hi=max(d-w,-R),min(d+w,R)\n"
            "  if hi<=lo: print(0.0); continue\n"
            "  a,_=dblquad(lambda y,x:1.0,lo,hi,lambda x:-math.sqrt(max(R*R-x*x,0)),"
            "lambda x:math.sqrt(max(R*R-x*x,0)),epsabs=1e-15,epsrel=1e-13)\n"
            "  print(repr(a))\n";
  std::istringstream output(test::run_python(script.str()));
  std::vector<double> areas;
  for (double area = 0.0; output >> area;) areas.push_back(area);
  return areas;
}

TEST(Footprint, SegmentAreaIdentities) {
  const double r = 0.3;
  EXPECT_NEAR(circle_segment_area_m2(0.0, r), 0.5 * kPi * r * r, 1e-15);
  EXPECT_EQ(circle_segment_area_m2(r, r), 0.0);
  EXPECT_EQ(circle_segment_area_m2(2 * r, r), 0.0);
  EXPECT_EQ(circle_segment_area_m2(-2 * r, r), kPi * r * r);
  for (double x = -0.3; x <= 0.3; x += 0.01) {
    EXPECT_NEAR(circle_segment_area_m2(x, r) + circle_segment_area_m2(-x, r), kPi * r * r, 1e-15);
  }
  EXPECT_EQ(circle_segment_area_m2(0.0, 0.0), 0.0);
  // The textbook form R²·acos(x/R) − x·√(R² − x²) in long double, across the switch between the
  // series and the closed form (at x = R·cos 0.25).
  for (int i = 0; i < 1000; ++i) {
    const long double x = 0.3L * i / 1000.0L, rl = r;
    const long double textbook = rl * rl * std::acos(x / rl) - x * std::sqrt(rl * rl - x * x);
    EXPECT_NEAR(circle_segment_area_m2(static_cast<double>(x), r), static_cast<double>(textbook),
                1e-15 * r * r)
        << "x = " << static_cast<double>(x);
  }
}

TEST(Footprint, OverlapMatchesScipyQuadrature) {
  const std::vector<double> oracle = scipy_overlaps();
  ASSERT_EQ(oracle.size(), kCases.size()) << "the scipy oracle did not run";
  for (std::size_t i = 0; i < kCases.size(); ++i) {
    const auto& c = kCases[i];
    SCOPED_TRACE(::testing::Message() << "d=" << c.d << " w=" << c.w << " R=" << c.r);
    EXPECT_NEAR(circle_strip_overlap_m2(c.d, c.w, c.r), oracle[i], 1e-11 * kPi * c.r * c.r);
  }
}

TEST(Footprint, LimitingGeometries) {
  EXPECT_EQ(circle_strip_overlap_m2(0.3, 0.01, 0.25), 0.0);          // fully off
  EXPECT_EQ(circle_strip_overlap_m2(0.0, 0.5, 0.25), kPi * 0.0625);  // wider than the disc
  EXPECT_EQ(footprint_fraction(0.0, 0.5, 0.25), 1.0);
  EXPECT_EQ(footprint_fraction(0.26, 0.01, 0.25), 0.0);          // touches nothing
  EXPECT_NEAR(footprint_fraction(0.0, 0.25, 0.25), 1.0, 1e-15);  // exactly the disc
  EXPECT_NEAR(footprint_fraction(0.5, 0.5, 1.0), 0.5, 1e-15);    // half the disc
}

// Source case 1 (eq 7.8): a strip covering past one side leaves a circular segment of height
// h = R − (d − w) — the exact formula equals it.
TEST(Footprint, EqualsSourceCase1WhenTheStripCoversPastOneSide) {
  // Eq 7.8 itself loses accuracy as h → 0 (acos near 1), so heights below 1e-3·R are left to
  // the scipy test.
  int checked = 0;
  for (const auto& c : kCases) {
    const double near_edge = c.d - c.w, far_edge = c.d + c.w;
    double height = -1.0;
    if (far_edge >= c.r && std::abs(near_edge) < c.r) height = c.r - near_edge;
    if (near_edge <= -c.r && std::abs(far_edge) < c.r) height = c.r + far_edge;  // the mirror
    if (height < 1e-3 * c.r) continue;
    EXPECT_NEAR(circle_strip_overlap_m2(c.d, c.w, c.r), segment_area_from_height_m2(height, c.r),
                1e-14 * c.r * c.r)
        << "d=" << c.d << " w=" << c.w << " R=" << c.r;
    ++checked;
  }
  EXPECT_GE(checked, 5);
  // A sweep of heights: h = 0 → nothing, h = R → half, h = 2R → the disc.
  EXPECT_NEAR(segment_area_from_height_m2(0.0, 0.4), 0.0, 1e-16);
  EXPECT_NEAR(segment_area_from_height_m2(0.4, 0.4), 0.5 * kPi * 0.16, 1e-15);
  EXPECT_NEAR(segment_area_from_height_m2(0.8, 0.4), kPi * 0.16, 1e-15);
  for (int i = 1; i <= 16; ++i) {
    const double h = 0.05 * i;
    EXPECT_NEAR(circle_strip_overlap_m2(0.4 - h + 1.0, 1.0, 0.4),
                segment_area_from_height_m2(h, 0.4), 1e-14);
  }
  // At a grazing edge the exact form stays accurate relative to the sliver it covers:
  // h = 1e-9·R gives (4/3)·√(2R)·h^{3/2} to leading order.
  const double r = 0.4, h = 1e-9 * r;
  const double sliver = circle_strip_overlap_m2(r - h + 1.0, 1.0, r);
  EXPECT_NEAR(sliver, 4.0 / 3.0 * std::sqrt(2.0 * r) * std::pow(h, 1.5), 1e-6 * sliver);
}

// Source case 2 (eq 7.9–7.10): a narrow central strip is chord × width; the relative error falls
// as (w/R)² — about w²/6R² at the centre.
TEST(Footprint, ApproachesSourceCase2ForNarrowStrips) {
  const double r = 0.25;
  for (const double d : {0.0, 0.075, -0.15}) {
    double previous = INFINITY;
    for (const double ratio : {1e-1, 1e-2, 1e-3, 1e-4}) {
      const double w = ratio * r;
      const double exact = circle_strip_overlap_m2(d, w, r);
      const double chord = chord_strip_area_m2(d, w, r);
      const double relative = std::abs(chord - exact) / exact;
      SCOPED_TRACE(::testing::Message() << "d=" << d << " w/R=" << ratio);
      const double scale = r * r / (r * r - d * d);
      EXPECT_LE(relative, 0.2 * ratio * ratio * scale * scale + 1e-10);
      EXPECT_GE(chord, exact);  // the chord is the widest cut: chord × width over-estimates
      EXPECT_LT(relative, previous);
      previous = relative;
    }
  }
  const double w = 1e-2 * r;
  EXPECT_NEAR(std::abs(chord_strip_area_m2(0.0, w, r) - circle_strip_overlap_m2(0.0, w, r)) /
                  circle_strip_overlap_m2(0.0, w, r),
              1e-4 / 6.0, 1e-7);
}

TEST(Footprint, FractionIsBoundedAndSymmetric) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const double r = 0.01 + unit(rng);
    const double w = 1.5 * unit(rng) * r;
    const double d = (4.0 * unit(rng) - 2.0) * r;
    const double f = footprint_fraction(d, w, r);
    ASSERT_GE(f, 0.0);
    ASSERT_LE(f, 1.0);
    EXPECT_NEAR(f, footprint_fraction(-d, w, r), 1e-14);
    EXPECT_NEAR(f, circle_strip_overlap_m2(d, w, r) / (kPi * r * r), 1e-15);
    // Moving the strip outward never increases its share.
    EXPECT_LE(footprint_fraction(std::abs(d) + 0.01 * r, w, r),
              footprint_fraction(d, w, r) + 1e-14);
  }
}

TEST(Footprint, PointBeamIsAllOrNothing) {
  EXPECT_EQ(footprint_fraction(0.005, 0.01, 0.0), 1.0);
  EXPECT_EQ(footprint_fraction(-0.005, 0.01, 0.0), 1.0);
  EXPECT_EQ(footprint_fraction(0.01, 0.01, 0.0), 0.5);
  EXPECT_EQ(footprint_fraction(0.02, 0.01, 0.0), 0.0);
}

}  // namespace
}  // namespace owsim
