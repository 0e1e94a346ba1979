// Protects the in-field clipping behind truth.csv's in_view (evaluation/field_of_view.hpp): the
// angles invert SENSOR-SPEC §4's ARC ray, and over random fields and segments the exact interval
// clip agrees with dense sampling along the segment — every segment with a sampled point inside is
// found, the point found is inside and no farther than the nearest sampled one; contains() is the
// angles' definition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "evaluation/field_of_view.hpp"
#include "sensor/mounting.hpp"

namespace owsim {
namespace {

Eigen::Vector3d src_of(double alpha_deg, double beta_deg, double range_m) {
  return range_m * src_from_arc(arc_unit_ray(alpha_deg, beta_deg));
}

// Inside with a tolerance in angle and range (the clip's boundary points are exact to rounding).
bool inside_loosely(const ScanField& field, const Eigen::Vector3d& v) {
  const FieldAngles angles = field_angles(v);
  constexpr double kDeg = 1e-7;
  return v.norm() <= field.range_max_m * (1 + 1e-9) &&
         angles.alpha_deg >= field.alpha_min_deg - kDeg &&
         angles.alpha_deg <= field.alpha_max_deg + kDeg &&
         angles.beta_deg >= field.beta_min_deg - kDeg &&
         angles.beta_deg <= field.beta_max_deg + kDeg;
}

// A random field: α bounds of either sign (the cones' four cases), β from `beta_lo` to at most
// 5° with a span up to `beta_span`, range 200-1300 m.
template <typename Uniform>
ScanField random_field(const Uniform& uniform, double beta_lo, double beta_span) {
  ScanField field;
  field.alpha_min_deg = uniform(-30.0, 10.0);
  field.alpha_max_deg = field.alpha_min_deg + uniform(0.5, 40.0);
  field.beta_min_deg = uniform(beta_lo, 5.0);
  field.beta_max_deg = field.beta_min_deg + uniform(0.5, beta_span);
  field.range_max_m = uniform(200.0, 1300.0);
  return field;
}

TEST(FieldOfView, AnglesInvertTheArcRay) {
  for (const double alpha : {-21.0, -3.5, 0.0, 7.25, 21.0}) {
    for (const double beta : {-18.2, -0.1, 0.0, 12.0, 18.2}) {
      const FieldAngles angles = field_angles(src_of(alpha, beta, 321.0));
      EXPECT_NEAR(angles.alpha_deg, alpha, 1e-12);
      EXPECT_NEAR(angles.beta_deg, beta, 1e-12);
    }
  }
}

TEST(FieldOfView, AnglesAreTheArcsineAndTheFourQuadrantArctangent) {
  // field_angles takes each angle as the arctangent of one quotient; the definition is
  // α = asin(a / |v|), β = atan2(b, c) (SENSOR-SPEC §4), over every direction, the axes included.
  constexpr double kDegPerRad = 180.0 / std::numbers::pi;
  const auto expect_definition = [&](const Eigen::Vector3d& v) {
    const FieldAngles angles = field_angles(v);
    EXPECT_NEAR(angles.alpha_deg, std::asin(v.y() / v.norm()) * kDegPerRad, 1e-12) << v.transpose();
    EXPECT_NEAR(angles.beta_deg, std::atan2(v.z(), v.x()) * kDegPerRad, 1e-12) << v.transpose();
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uniform(-1500.0, 1500.0);
  for (int trial = 0; trial < 100000; ++trial) {
    expect_definition({uniform(rng), 0.1 * uniform(rng), uniform(rng)});
  }
  for (const double x : {-2.0, -0.0, 0.0, 3.0}) {
    for (const double y : {-5.0, -0.0, 0.0, 1.0}) {
      for (const double z : {-7.0, -0.0, 0.0, 4.0}) {
        if (x != 0.0 || y != 0.0 || z != 0.0) expect_definition({x, y, z});
      }
    }
  }
  const FieldAngles origin = field_angles(Eigen::Vector3d::Zero());
  EXPECT_EQ(origin.alpha_deg, 0.0);
  EXPECT_EQ(origin.beta_deg, 0.0);
}

TEST(FieldOfView, ContainsIsTheAnglesAndRangeWithinTheBounds) {
  // contains() tests half-spaces and cones; the definition is α, β and range within the bounds.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const ScanField field = random_field(uniform, -40.0, 40.0);
    const FieldOfView fov(field);
    // Anywhere, or (every other trial) near the field, to reach its bounds often.
    const Eigen::Vector3d v =
        trial % 2 == 0
            ? Eigen::Vector3d(uniform(-1400, 1400), uniform(-900, 900), uniform(-900, 900))
            : src_of(uniform(field.alpha_min_deg - 3, field.alpha_max_deg + 3),
                     uniform(field.beta_min_deg - 3, field.beta_max_deg + 3),
                     uniform(0.0, 1.1 * field.range_max_m));
    const FieldAngles a = field_angles(v);
    const double length = v.norm();
    // Away from a bound by more than rounding: both forms must answer alike.
    constexpr double kDeg = 1e-9;
    const double margin =
        std::min({std::abs(a.alpha_deg - field.alpha_min_deg),
                  std::abs(a.alpha_deg - field.alpha_max_deg),
                  std::abs(a.beta_deg - field.beta_min_deg),
                  std::abs(a.beta_deg - field.beta_max_deg),
                  std::abs(length - field.range_max_m) / field.range_max_m});
    if (margin < kDeg) continue;
    const bool by_angles = length <= field.range_max_m && a.alpha_deg >= field.alpha_min_deg &&
                           a.alpha_deg <= field.alpha_max_deg &&
                           a.beta_deg >= field.beta_min_deg && a.beta_deg <= field.beta_max_deg;
    ASSERT_EQ(fov.contains(v), by_angles) << "trial " << trial;
    (by_angles ? inside : outside) += 1;
  }
  EXPECT_GT(inside, 20000);
  EXPECT_GT(outside, 100000);
}

TEST(FieldOfView, AWireAcrossTheFieldIsInViewAtItsNearestPoint) {
  const FieldOfView field({-21.0, 21.0, -18.0, 18.0, 1238.36});
  // A horizontal wire 300 m ahead, 10 m above, crossing from left to right (SRC: X forward,
  // Y = ARC a = up for this test's α, Z = ARC b = right).
  const Eigen::Vector3d from(300.0, 10.0, -500.0), to(300.0, 10.0, 500.0);
  const std::optional<double> t = field.nearest_inside(from, to);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, 1e-12);  // straight ahead is nearest and in the field
  // The same wire 10° above the highest fiber's α is out of view.
  const double high = 300.0 * std::tan((21.0 + 10.0) * std::numbers::pi / 180.0);
  EXPECT_FALSE(field.nearest_inside({300.0, high, -500.0}, {300.0, high, 500.0}).has_value());
  // Beyond the timeout range.
  EXPECT_FALSE(field.nearest_inside({1300.0, 0.0, -50.0}, {1300.0, 0.0, 50.0}).has_value());
  // Behind the sensor.
  EXPECT_FALSE(field.nearest_inside({-300.0, 0.0, -50.0}, {-300.0, 0.0, 50.0}).has_value());
}

TEST(FieldOfView, ClipAgreesWithDenseSamplingOverRandomFieldsAndSegments) {
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  constexpr int kSamples = 4001;
  int found_by_both = 0, inside_only_by_clip = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const ScanField field = random_field(uniform, -30.0, 30.0);  // β within ±30°
    const FieldOfView fov(field);
    const auto point = [&] {
      return Eigen::Vector3d(uniform(-400, 1400), uniform(-500, 500), uniform(-700, 700));
    };
    const Eigen::Vector3d p0 = point();
    const Eigen::Vector3d p1 =
        trial % 5 == 0 ? p0 + Eigen::Vector3d(0, uniform(-50, 50), 0) : point();
    double sampled_best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < kSamples; ++i) {
      const Eigen::Vector3d v = p0 + (static_cast<double>(i) / (kSamples - 1)) * (p1 - p0);
      if (fov.contains(v)) sampled_best = std::min(sampled_best, v.norm());
    }
    const std::optional<double> t = fov.nearest_inside(p0, p1);
    if (std::isfinite(sampled_best)) {
      ASSERT_TRUE(t.has_value()) << "trial " << trial;
      ++found_by_both;
    } else if (t) {
      ++inside_only_by_clip;  // a sliver between samples: the point must still be inside
    }
    if (!t) continue;
    ASSERT_GE(*t, 0.0);
    ASSERT_LE(*t, 1.0);
    const Eigen::Vector3d found = p0 + *t * (p1 - p0);
    ASSERT_TRUE(inside_loosely(field, found)) << "trial " << trial;
    if (std::isfinite(sampled_best)) {
      ASSERT_LE(found.norm(), sampled_best + 1e-9 * field.range_max_m) << "trial " << trial;
    }
  }
  EXPECT_GT(found_by_both, 150);  // the random cases reach the field often enough to mean something
  EXPECT_LT(inside_only_by_clip, 30);
}

TEST(FieldOfView, ASphereWithAPointInsideIsNeverRuledOut) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  const FieldOfView field({-21.0, 21.0, -18.3, 17.9, 1238.36});
  int ruled_out = 0, holding = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Eigen::Vector3d centre(uniform(-300, 1500), uniform(-800, 800), uniform(-800, 800));
    const double radius = uniform(0.5, 200.0);
    bool inside = false;
    for (int k = 0; k < 400 && !inside; ++k) {
      Eigen::Vector3d offset(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      if (offset.norm() > 1.0) continue;
      inside = field.contains(centre + radius * offset);
    }
    if (inside) {
      ++holding;
      ASSERT_TRUE(field.may_hold_sphere(centre, radius)) << trial;
    } else if (!field.may_hold_sphere(centre, radius)) {
      ++ruled_out;
    }
  }
  EXPECT_GT(holding, 200);
  EXPECT_GT(ruled_out, 1000);  // the test rules out most spheres that are outside
}

TEST(FieldOfView, NearestOnSegmentClampsToTheEnds) {
  EXPECT_DOUBLE_EQ(nearest_on_segment({1, -1, 0}, {1, 1, 0}), 0.5);
  EXPECT_DOUBLE_EQ(nearest_on_segment({1, 1, 0}, {1, 3, 0}), 0.0);
  EXPECT_DOUBLE_EQ(nearest_on_segment({1, -3, 0}, {1, -1, 0}), 1.0);
  EXPECT_DOUBLE_EQ(nearest_on_segment({2, 0, 0}, {2, 0, 0}), 0.0);
}

}  // namespace
}  // namespace owsim
