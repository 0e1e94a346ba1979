// Protects the catenary of SENSOR-SPEC §6 (eq 6.11–6.14): both supports on the curve to < 1 mm
// for equal and unequal supports, the parameter against an independent scipy solve, the vertex
// at S, the rejected inputs, and the polyline sampling within 1 mm with a modest point count.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "geometry/catenary.hpp"
#include "geometry/error.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

using test::run_python;

constexpr double kOnCurve = 1e-6;  // far inside the spec's 1 mm

// An independent solve (scipy brentq): for a vertex position x0, the a that puts support 1 on
// the curve, then the x0 that puts support 2 on it. Returns {a, x0}.
std::array<double, 2> scipy_catenary(const CatenaryProfile& p) {
  std::ostringstream script;
  script.precision(17);
  script << "import math\n"
            "from scipy.optimize import brentq\n"
            "D, H1, H2, S = "
         << p.span_m << ", " << p.support_1_m << ", " << p.support_2_m << ", " << p.lowest_m
         << "\n"
            "h1, h2 = H1 - S, H2 - S\n"
            "def a_for(x0):\n"
            "    g = lambda a: a * (math.cosh(x0 / a) - 1.0) - h1\n"
            "    return brentq(g, x0 / 700.0, 1e12, xtol=1e-300, rtol=1e-15, maxiter=2000)\n"
            "def r(x0):\n"
            "    a = a_for(x0)\n"
            "    z = (D - x0) / a\n"
            "    return 1e300 if z > 700 else a * (math.cosh(z) - 1.0) - h2\n"
            "x0 = brentq(r, D * 1e-9, D * (1 - 1e-9), xtol=1e-300, rtol=1e-15, maxiter=2000)\n"
            "print(repr(a_for(x0)), repr(x0))\n";
  std::istringstream output(run_python(script.str()));
  std::array<double, 2> result{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};
  output >> result[0] >> result[1];
  return result;
}

void expect_supports_on_curve(const Catenary& c) {
  const CatenaryProfile& p = c.profile();
  EXPECT_NEAR(c.height_at(0.0), p.support_1_m, kOnCurve);
  EXPECT_NEAR(c.height_at(p.span_m), p.support_2_m, kOnCurve);
  EXPECT_NEAR(c.height_at(c.vertex_x_m()), p.lowest_m, 1e-12);
  EXPECT_NEAR(c.slope_at(c.vertex_x_m()), 0.0, 1e-15);
  EXPECT_GE(c.vertex_x_m(), 0.0);
  EXPECT_LE(c.vertex_x_m(), p.span_m);
}

// Largest perpendicular distance between the curve and its sampled polyline, checked at 200
// points inside every segment.
double max_chord_error_m(const Catenary& c, const std::vector<double>& xs) {
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    const double x0 = xs[i], x1 = xs[i + 1];
    const double y0 = c.height_at(x0), y1 = c.height_at(x1);
    const double dx = x1 - x0, dy = y1 - y0, length = std::hypot(dx, dy);
    for (int k = 1; k < 200; ++k) {
      const double x = x0 + dx * k / 200.0, y = c.height_at(x);
      worst = std::max(worst, std::abs((x - x0) * dy - (y - y0) * dx) / length);
    }
  }
  return worst;
}

void expect_sampling_within_1mm(const Catenary& c, std::size_t max_points) {
  const std::vector<double> xs = c.sample_x();
  ASSERT_GE(xs.size(), 2u);
  EXPECT_EQ(xs.front(), 0.0);
  EXPECT_EQ(xs.back(), c.profile().span_m);
  EXPECT_TRUE(std::is_sorted(xs.begin(), xs.end()));
  EXPECT_LT(max_chord_error_m(c, xs), 1e-3);
  EXPECT_LE(xs.size(), max_points);
}

// Simpson's rule on √(1 + y'²), an independent arc length.
double simpson_length_m(const Catenary& c) {
  const int n = 20000;
  const double d = c.profile().span_m, h = d / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += weight * std::sqrt(1.0 + std::pow(c.slope_at(i * h), 2));
  }
  return sum * h / 3.0;
}

TEST(Catenary, SymmetricSpanHasItsVertexInTheMiddle) {
  const Catenary c = Catenary::solve({400.0, 30.0, 30.0, 20.0});
  EXPECT_NEAR(c.vertex_x_m(), 200.0, 1e-9);
  expect_supports_on_curve(c);
  // Closed form of the symmetric case: a·(cosh(D/2a) − 1) = H − S.
  const double a = c.parameter_m();
  EXPECT_NEAR(a * (std::cosh(200.0 / a) - 1.0), 10.0, 1e-9);
  const auto [a_scipy, x0_scipy] = scipy_catenary(c.profile());
  EXPECT_NEAR(a, a_scipy, 1e-9 * a_scipy);
  EXPECT_NEAR(c.vertex_x_m(), x0_scipy, 1e-6);
  EXPECT_NEAR(a, 2000.0, 5.0);  // ≈ D²/(8·sag) for a shallow span
}

TEST(Catenary, SourceExampleIsOffCentreTowardsTheLowerSupport) {
  // SENSOR-SPEC §6: H1 = 100 m, H2 = 57 m, S = 45 m, D = 112 m (source illustration 9).
  const Catenary c = Catenary::solve({112.0, 100.0, 57.0, 45.0});
  expect_supports_on_curve(c);
  EXPECT_GT(c.vertex_x_m(), 56.0);  // support 2 (x = D) is the lower one
  const auto [a_scipy, x0_scipy] = scipy_catenary(c.profile());
  EXPECT_NEAR(c.parameter_m(), a_scipy, 1e-9 * a_scipy);
  EXPECT_NEAR(c.vertex_x_m(), x0_scipy, 1e-6);
  // The vertex offsets obey the catenary relation on each side.
  const double a = c.parameter_m();
  EXPECT_NEAR(a * (std::cosh(c.vertex_x_m() / a) - 1.0), 55.0, 1e-7);
  EXPECT_NEAR(a * (std::cosh((112.0 - c.vertex_x_m()) / a) - 1.0), 12.0, 1e-7);
  EXPECT_NEAR(c.length_m(), simpson_length_m(c), 1e-7);
}

TEST(Catenary, NearFlatSpan) {
  const Catenary c = Catenary::solve({300.0, 30.0, 30.0, 29.99});
  expect_supports_on_curve(c);
  EXPECT_NEAR(c.vertex_x_m(), 150.0, 1e-6);
  const double a = c.parameter_m();
  EXPECT_NEAR(2.0 * a * std::pow(std::sinh(75.0 / a), 2), 0.01, 1e-12);
  EXPECT_NEAR(a, 300.0 * 300.0 / (8.0 * 0.01), 10.0);
  EXPECT_NEAR(c.length_m(), simpson_length_m(c), 1e-7);
}

TEST(Catenary, DeepSag) {
  const Catenary c = Catenary::solve({50.0, 100.0, 100.0, 1.0});
  expect_supports_on_curve(c);
  EXPECT_NEAR(c.vertex_x_m(), 25.0, 1e-9);
  const auto [a_scipy, x0_scipy] = scipy_catenary(c.profile());
  EXPECT_NEAR(c.parameter_m(), a_scipy, 1e-9 * a_scipy);
  EXPECT_GT(std::abs(c.slope_at(0.0)), 5.0);  // steep at the supports
  EXPECT_NEAR(c.length_m(), simpson_length_m(c), 1e-6);
}

TEST(Catenary, LowestPointAtTheLowerSupport) {
  const Catenary at_2 = Catenary::solve({200.0, 40.0, 30.0, 30.0});
  expect_supports_on_curve(at_2);
  EXPECT_NEAR(at_2.vertex_x_m(), 200.0, 1e-9);
  EXPECT_NEAR(at_2.slope_at(200.0), 0.0, 1e-9);
  const Catenary at_1 = Catenary::solve({200.0, 30.0, 40.0, 30.0});
  expect_supports_on_curve(at_1);
  EXPECT_NEAR(at_1.vertex_x_m(), 0.0, 1e-9);
  EXPECT_NEAR(at_1.parameter_m(), at_2.parameter_m(), 1e-9 * at_2.parameter_m());
}

TEST(Catenary, RejectsImpossibleSpans) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)Catenary::solve({100.0, 30.0, 30.0, 31.0}), Error);  // S above both
  EXPECT_THROW((void)Catenary::solve({100.0, 30.0, 40.0, 35.0}), Error);  // S above support 1
  EXPECT_THROW((void)Catenary::solve({100.0, 40.0, 30.0, 35.0}), Error);  // S above support 2
  EXPECT_THROW((void)Catenary::solve({0.0, 30.0, 30.0, 20.0}), Error);
  EXPECT_THROW((void)Catenary::solve({-10.0, 30.0, 30.0, 20.0}), Error);
  EXPECT_THROW((void)Catenary::solve({nan, 30.0, 30.0, 20.0}), Error);
  EXPECT_THROW((void)Catenary::solve({100.0, nan, 30.0, 20.0}), Error);
  EXPECT_THROW((void)Catenary::solve({100.0, 30.0, nan, 20.0}), Error);
  EXPECT_THROW((void)Catenary::solve({100.0, 30.0, 30.0, nan}), Error);
  EXPECT_THROW((void)Catenary::solve({100.0, 30.0, 30.0, 30.0}), Error);     // no sag at all
  EXPECT_THROW((void)Catenary::solve({1e-13, 1000.0, 1000.0, 0.0}), Error);  // hangs vertically
  try {
    (void)Catenary::solve({100.0, 30.0, 40.0, 35.0});
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("above a support"), std::string::npos) << error.what();
  }
}

TEST(Catenary, SampledPolylineStaysWithinOneMillimetre) {
  const Catenary symmetric = Catenary::solve({400.0, 30.0, 30.0, 20.0});
  expect_sampling_within_1mm(symmetric, 300);
  // Not oversampled either: the worst chord error uses most of the bound.
  EXPECT_GT(max_chord_error_m(symmetric, symmetric.sample_x()), 0.5e-3);
  const Catenary source = Catenary::solve({112.0, 100.0, 57.0, 45.0});
  expect_sampling_within_1mm(source, 300);
  EXPECT_GT(max_chord_error_m(source, source.sample_x()), 0.5e-3);
  expect_sampling_within_1mm(Catenary::solve({300.0, 30.0, 30.0, 29.99}), 20);
  expect_sampling_within_1mm(Catenary::solve({50.0, 100.0, 100.0, 1.0}), 1000);
  expect_sampling_within_1mm(Catenary::solve({200.0, 40.0, 30.0, 30.0}), 300);
  // A coarser bound gives fewer points and still holds.
  const std::vector<double> coarse = symmetric.sample_x(0.05);
  EXPECT_LT(coarse.size(), symmetric.sample_x().size());
  EXPECT_LT(max_chord_error_m(symmetric, coarse), 0.05);
  EXPECT_THROW((void)symmetric.sample_x(0.0), Error);
  EXPECT_THROW((void)symmetric.sample_x(std::numeric_limits<double>::quiet_NaN()), Error);
}

}  // namespace
}  // namespace owsim
