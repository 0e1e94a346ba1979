// Protects the natural cubic spline of SENSOR-SPEC §5 (source eq 10.2–10.3): it interpolates the
// knots, has zero curvature at the ends, is C², is exact on straight lines, and matches
// scipy.interpolate.CubicSpline(bc_type='natural') in value and slope.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "python_oracle.hpp"
#include "sensor/cubic_spline.hpp"

namespace owsim {
namespace {

using test::python_list;
using test::run_python;

// Random strictly increasing knots with uneven steps, and random values.
void random_knots(std::size_t n, std::uint64_t seed, std::vector<double>& x,
                  std::vector<double>& y) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> step(0.05, 1.0), value(-10.0, 10.0);
  x = {0.3};
  for (std::size_t i = 1; i < n; ++i) x.push_back(x.back() + step(rng));
  y.clear();
  for (std::size_t i = 0; i < n; ++i) y.push_back(value(rng));
}

TEST(CubicSpline, InterpolatesTheKnots) {
  std::vector<double> x, y;
  random_knots(50, 1, x, y);
  const CubicSpline spline(x, y);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(spline.value(x[i]), y[i], 1e-12) << i;
}

TEST(CubicSpline, NaturalEndsHaveZeroCurvature) {
  std::vector<double> x, y;
  random_knots(30, 2, x, y);
  const CubicSpline spline(x, y);
  EXPECT_EQ(spline.second_derivatives().front(), 0.0);
  EXPECT_EQ(spline.second_derivatives().back(), 0.0);
  // Independently of the stored z: the slope's finite difference at the ends.
  const double h = 1e-6;
  EXPECT_NEAR((spline.derivative(x.front() + h) - spline.derivative(x.front())) / h, 0.0, 1e-3);
  EXPECT_NEAR((spline.derivative(x.back()) - spline.derivative(x.back() - h)) / h, 0.0, 1e-3);
  EXPECT_GT(std::abs(spline.second_derivative(0.5 * (x[10] + x[11]))), 1e-3);  // not all flat
}

TEST(CubicSpline, SlopeAndCurvatureAreContinuousAtInnerKnots) {
  std::vector<double> x, y;
  random_knots(25, 3, x, y);
  const CubicSpline spline(x, y);
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    const CubicSpline::Sample left = spline.evaluate_in(i - 1, x[i]);
    const CubicSpline::Sample right = spline.evaluate_in(i, x[i]);
    EXPECT_NEAR(left.value, right.value, 1e-12);
    EXPECT_NEAR(left.derivative, right.derivative, 1e-10) << i;
  }
  const double h = 1e-5;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    const double left = (spline.evaluate_in(i - 1, x[i]).derivative -
                         spline.evaluate_in(i - 1, x[i] - h).derivative) /
                        h;
    const double right =
        (spline.evaluate_in(i, x[i] + h).derivative - spline.evaluate_in(i, x[i]).derivative) / h;
    EXPECT_NEAR(left, right, 1e-2 * (1.0 + std::abs(left))) << i;
  }
}

TEST(CubicSpline, MatchesScipyNaturalCubicSpline) {
  std::vector<double> x, y;
  random_knots(40, 4, x, y);
  std::vector<double> at;
  for (int k = 0; k < 1000; ++k) at.push_back(x.front() + (x.back() - x.front()) * k / 999.0);
  std::ostringstream script;
  script << "import numpy as np\nfrom scipy.interpolate import CubicSpline\n"
         << "s = CubicSpline(np.array(" << python_list(x) << "), np.array(" << python_list(y)
         << "), bc_type='natural')\n"
         << "t = np.array(" << python_list(at) << ")\n"
         << "print(' '.join(repr(float(v)) for v in s(t)))\n"
         << "print(' '.join(repr(float(v)) for v in s(t, 1)))\n";
  std::istringstream output(run_python(script.str()));
  const CubicSpline spline(x, y);
  for (std::size_t k = 0; k < at.size(); ++k) {
    double expected = 0.0;
    ASSERT_TRUE(output >> expected);
    EXPECT_NEAR(spline.value(at[k]), expected, 1e-9) << at[k];
  }
  for (std::size_t k = 0; k < at.size(); ++k) {
    double expected = 0.0;
    ASSERT_TRUE(output >> expected);
    EXPECT_NEAR(spline.derivative(at[k]), expected, 1e-9) << at[k];
  }
}

TEST(CubicSpline, ExactOnStraightLines) {
  std::vector<double> x, y;
  random_knots(20, 5, x, y);
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = -3.0 + 2.5 * x[i];
  const CubicSpline spline(x, y);
  for (double z : spline.second_derivatives()) EXPECT_NEAR(z, 0.0, 1e-12);
  for (int k = 0; k <= 500; ++k) {
    const double t = x.front() + (x.back() - x.front()) * k / 500.0;
    EXPECT_NEAR(spline.value(t), -3.0 + 2.5 * t, 1e-12);
    EXPECT_NEAR(spline.derivative(t), 2.5, 1e-12);
  }
  const CubicSpline two({0.0, 2.0}, {1.0, 5.0});  // two knots: the straight line
  EXPECT_DOUBLE_EQ(two.value(0.5), 2.0);
  EXPECT_DOUBLE_EQ(two.derivative(1.7), 2.0);
}

TEST(CubicSpline, HoldsTheEndValuesOutsideTheRange) {
  const CubicSpline spline({0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 0.0, 4.0});
  EXPECT_EQ(spline.value(-1.0), 0.0);
  EXPECT_EQ(spline.derivative(-1.0), 0.0);
  EXPECT_EQ(spline.value(7.0), 4.0);
  EXPECT_EQ(spline.derivative(7.0), 0.0);
  EXPECT_EQ(spline.interval(-5.0), 0u);
  EXPECT_EQ(spline.interval(3.0), 2u);
  EXPECT_EQ(spline.interval(1.0), 1u);
  EXPECT_NEAR(spline.value(3.0), 4.0, 1e-15);
}

TEST(CubicSpline, RejectsBadKnots) {
  EXPECT_THROW(CubicSpline({0.0}, {1.0}), Error);
  EXPECT_THROW(CubicSpline({0.0, 1.0}, {1.0}), Error);
  EXPECT_THROW(CubicSpline({0.0, 1.0, 1.0}, {1.0, 2.0, 3.0}), Error);
  EXPECT_THROW(CubicSpline({0.0, 2.0, 1.0}, {1.0, 2.0, 3.0}), Error);
  try {
    const CubicSpline spline({0.0, 1.0, 2.0}, {1.0, std::numeric_limits<double>::quiet_NaN(), 3.0});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("knot 1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace owsim
