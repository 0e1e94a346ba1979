// Protects the reference obstacle detector (detection/, DETECTION-SPEC): the source's class rules
// at their own numbers, the ground estimate, the plan extents, and the whole detector on a
// synthetic scene — a wire, a pole, a tree, the ground and false returns — classed, tracked with
// ids kept, held for hold_s and dropped after, bit for bit the same on a second run; and the
// `detector:` keys' ranges equal to the scenario's table.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "detection/ground_map.hpp"
#include "detection/obstacle_detector.hpp"
#include "detection/plan_cells.hpp"
#include "geometry/error.hpp"
#include "io/scenario/value_ranges.hpp"

namespace owsim {
namespace {

TEST(ObstacleRules, TheSourcesNumbers) {
  const DetectorParams p;
  // WIRE: length / width > 20 (ch. 1).
  EXPECT_FALSE(wire_shaped(20.0, 1.0, p));
  EXPECT_TRUE(wire_shaped(20.01, 1.0, p));
  ObstacleShape wire{.length_m = 100.0, .width_m = 1.0, .clearance_m = 5.0, .isolated_share = 0.75};
  EXPECT_TRUE(wire_rule(wire, p));
  wire.clearance_m = 4.99;  // ≥ 5 m above the visible ground
  EXPECT_FALSE(wire_rule(wire, p));
  wire.clearance_m = 5.0;
  wire.isolated_share = 0.74;  // ≥ 5 m from other objects
  EXPECT_FALSE(wire_rule(wire, p));

  // POLE: visible height > 5 m, width / height < 1/5, width < 10 m.
  ObstacleShape pole{.length_m = 0.6, .width_m = 0.6, .height_m = 5.01};
  EXPECT_EQ(solid_class(pole, p), ObstacleClass::pole);
  pole.height_m = 5.0;
  EXPECT_NE(solid_class(pole, p), ObstacleClass::pole);
  pole = {.length_m = 2.0, .width_m = 2.0, .height_m = 10.0};  // width / height = 1/5
  EXPECT_NE(solid_class(pole, p), ObstacleClass::pole);
  pole = {.length_m = 10.0, .width_m = 1.0, .height_m = 200.0};  // 10 m long: a wall, not a pole
  EXPECT_NE(solid_class(pole, p), ObstacleClass::pole);

  // TREE: visible height > 3 m, width ≤ 25 m, isolated by ≥ 5 × its width.
  ObstacleShape tree{.length_m = 25.0, .width_m = 25.0, .height_m = 3.01, .isolation_m = 125.0};
  EXPECT_EQ(solid_class(tree, p), ObstacleClass::tree);
  tree.isolation_m = 124.9;
  EXPECT_EQ(solid_class(tree, p), ObstacleClass::none);
  tree = {.length_m = 25.0, .width_m = 25.01, .height_m = 10.0, .isolation_m = 1000.0};
  EXPECT_EQ(solid_class(tree, p), ObstacleClass::none);
  tree = {.length_m = 6.0, .width_m = 6.0, .height_m = 3.0, .isolation_m = 1000.0};
  EXPECT_EQ(solid_class(tree, p), ObstacleClass::none);
}

TEST(ObstacleRules, PlanExtentOfARotatedRectangle) {
  // Points filling a 40 × 4 m rectangle turned 30° from east: length 40 and width 4, within the
  // sampling's edge.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> along(-20.0, 20.0), across(-2.0, 2.0);
  const double t = 30.0 * M_PI / 180.0;
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 4000; ++k) {
    const double s = along(rng), w = across(rng);
    points.emplace_back(100.0 + s * std::cos(t) - w * std::sin(t), -50.0 + s * std::sin(t) + w * std::cos(t),
                        7.0);
  }
  const PlanExtent extent = plan_extent(points);
  EXPECT_NEAR(extent.length_m, 40.0, 0.1);
  EXPECT_NEAR(extent.width_m, 4.0, 0.05);
  EXPECT_NEAR(std::abs(extent.axis.dot(Eigen::Vector2d(std::cos(t), std::sin(t)))), 1.0, 1e-4);
}

// The closed-form principal axis against Eigen's own eigensolver over random plan covariances, and
// the degenerate cases it must settle.
TEST(ObstacleRules, PrincipalAxisIsTheEigensolversLargerEigenvector) {
  std::mt19937_64 rng(69);
  std::uniform_real_distribution<double> spread(-50.0, 50.0);
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Matrix2d m;
    const Eigen::Vector2d u(spread(rng), spread(rng)), v(spread(rng), spread(rng));
    m = u * u.transpose() + 0.1 * v * v.transpose();  // positive semi-definite, as covariances are
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(m);
    if (solver.eigenvalues()(1) - solver.eigenvalues()(0) < 1e-6 * solver.eigenvalues()(1)) {
      continue;  // no preferred direction to compare
    }
    const Eigen::Vector2d expected = solver.eigenvectors().col(1);
    const Eigen::Vector2d axis = principal_axis(m(0, 0), m(0, 1), m(1, 1));
    EXPECT_NEAR(axis.norm(), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(axis.dot(expected)), 1.0, 1e-9) << m;
  }
  EXPECT_EQ(principal_axis(4.0, 0.0, 1.0), Eigen::Vector2d(1.0, 0.0));
  EXPECT_EQ(principal_axis(1.0, 0.0, 4.0), Eigen::Vector2d(0.0, 1.0));
  EXPECT_EQ(principal_axis(2.0, 0.0, 2.0), Eigen::Vector2d::UnitX());  // isotropic
  EXPECT_EQ(principal_axis(0.0, 0.0, 0.0), Eigen::Vector2d::UnitX());  // one point
}

TEST(PlanCells, CellIndexIsTheFloorOfTheQuotient) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> any(-3000.0, 3000.0);
  for (int k = 0; k < 20000; ++k) {
    const double x = k < 8 ? std::vector<double>{-5.0, -0.0, 0.0, 5.0, -10.0, 4.999999, -1e-300,
                                                 2999.9999999}[static_cast<std::size_t>(k)]
                           : any(rng);
    for (const double size : {1.0, 5.0, 0.25}) {
      EXPECT_EQ(cell_index(x, size), static_cast<std::int64_t>(std::floor(x / size))) << x;
    }
  }
  // Keys sort as (i, j) do; (i, j + 1) is one more; the indices come back.
  EXPECT_LT(plan_cell_key(std::int64_t{-1}, 7), plan_cell_key(std::int64_t{0}, -7));
  EXPECT_EQ(plan_cell_key(std::int64_t{-3}, -1) + 1, plan_cell_key(std::int64_t{-3}, 0));
  EXPECT_EQ(plan_cell_i(plan_cell_key(std::int64_t{-3}, 9)), -3);
  EXPECT_EQ(plan_cell_j(plan_cell_key(std::int64_t{-3}, -9)), -9);
}

TEST(PlanCells, SortByCellIsTheComparisonSortByCellThenPoint) {
  std::mt19937_64 rng(5);
  std::vector<CellPoint> none, one{{plan_cell_key(-3.5, 2.0, 1.0), 7}}, buffer;
  sort_by_cell(none, buffer);  // no points: no box, nothing to do
  EXPECT_TRUE(none.empty());
  sort_by_cell(one, buffer);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].point, 7u);
  // A few metres, a window of kilometres, and cells too far apart for the radix sort's box.
  for (const double spread : {3.0, 2500.0, 1e9}) {
    std::uniform_real_distribution<double> any(-spread, spread);
    std::vector<CellPoint> cell_points, buffer;
    for (std::uint32_t p = 0; p < 5000; ++p) {
      cell_points.push_back({plan_cell_key(any(rng), any(rng), 1.0), p});
    }
    std::vector<CellPoint> expected = cell_points;
    std::sort(expected.begin(), expected.end(), [](const CellPoint& a, const CellPoint& b) {
      return a.key != b.key ? a.key < b.key : a.point < b.point;
    });
    sort_by_cell(cell_points, buffer);
    ASSERT_EQ(cell_points.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      EXPECT_EQ(cell_points[k].key, expected[k].key) << spread << " at " << k;
      EXPECT_EQ(cell_points[k].point, expected[k].point) << spread << " at " << k;
    }
  }
}

TEST(GroundMap, TheLowestPairOfAgreeingReturnsOfACellIsItsGround) {
  GroundMap ground(5.0, 1500.0);
  EXPECT_TRUE(std::isnan(ground.ground_u(1.0, 1.0)));
  ground.add(1.0, 1.0, -400.0);  // a false return below the ground: alone, no ground
  EXPECT_TRUE(std::isnan(ground.ground_u(1.0, 1.0)));
  ground.add(2.0, 2.0, 3.0);  // two that disagree by more than kAgreeM: still none
  EXPECT_TRUE(std::isnan(ground.ground_u(1.0, 1.0)));
  ground.add(2.0, 2.0, 2.5);  // a surface seen twice: the higher of the pair
  EXPECT_EQ(ground.ground_u(1.0, 1.0), 3.0);
  ground.add(3.0, 3.0, 1.0);  // 1.0 agrees with nothing kept
  EXPECT_EQ(ground.ground_u(1.0, 1.0), 3.0);
  ground.add(3.0, 3.0, 0.8);
  EXPECT_EQ(ground.ground_u(1.0, 1.0), 1.0);
  // Two more false returns far below, each alone: the ground stays (kKept = 4 lowest kept).
  ground.add(3.0, 3.0, -30.0);
  EXPECT_EQ(ground.ground_u(1.0, 1.0), 1.0);
  ground.add(3.0, 3.0, -55.0);  // the kept: −400, −55, −30, 0.8: 1.0 is no longer among them
  EXPECT_TRUE(std::isnan(ground.ground_u(1.0, 1.0)));
  // The 3×3 cells around: a neighbour's lower ground counts, one two cells away does not.
  ground.add(7.0, 1.0, 0.5);
  ground.add(7.5, 1.5, 0.25);
  EXPECT_EQ(ground.ground_u(1.0, 1.0), 0.5);
  ground.add(12.0, 1.0, -5.0);
  ground.add(12.0, 1.0, -5.0);
  EXPECT_EQ(ground.ground_u(1.0, 1.0), 0.5);
  EXPECT_EQ(ground.ground_u(8.0, 1.0), -5.0);
  // A cell a whole table away takes the slot over; the old one is forgotten.
  GroundMap small(5.0, 10.0);
  small.add(1.0, 1.0, 2.0);
  small.add(1.0, 1.0, 2.0);
  EXPECT_EQ(small.ground_u(1.0, 1.0), 2.0);
  const double side = 5.0 * (std::ceil(2.0 * 10.0 / 5.0) + 4);
  small.add(1.0 + side, 1.0, 9.0);
  EXPECT_TRUE(std::isnan(small.ground_u(1.0, 1.0)));
  // Across the table's edge (cell −1 lies in the last slot of its row) and below zero.
  GroundMap edge(5.0, 10.0);
  edge.add(-2.0, -2.0, 4.0);
  edge.add(-2.0, -2.0, 4.0);
  EXPECT_EQ(edge.ground_u(1.0, 1.0), 4.0);    // cell (0, 0) sees (−1, −1)
  EXPECT_EQ(edge.ground_u(-6.0, -6.0), 4.0);  // cell (−2, −2) sees it too
  EXPECT_TRUE(std::isnan(edge.ground_u(-12.0, -2.0)));  // (−3, −1): two cells away
  EXPECT_TRUE(std::isnan(edge.ground_u(-2.0 - side, -2.0)));  // its slot, another cell
  edge.add(-2.0 - 3.0 * side, -2.0, 9.0);  // three tables away takes the slot over
  EXPECT_TRUE(std::isnan(edge.ground_u(-2.0, -2.0)));
}

// A synthetic scene seen from (−400, 0, 60): flat ground at 0 from e = −300 to 400, a wire across
// the track at e = 150 sagging from 29 m to 25 m, a 30 m pole 0.4 m wide at (50, 40), a 12 m tree
// 6 m wide at (250, −70), and false returns anywhere. Each frame samples every surface afresh.
struct SyntheticScene {
  bool wire = true, pole = true, tree = true;
  std::vector<Eigen::Vector3d> frame(std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> noise(0.0, 0.1);
    std::vector<Eigen::Vector3d> out;
    for (int k = 0; k < 6000; ++k) {
      out.emplace_back(-300.0 + 700.0 * unit(rng), -200.0 + 400.0 * unit(rng), noise(rng) * 0.2);
    }
    if (wire) {
      for (int k = 0; k < 60; ++k) {
        const double n = -120.0 + 240.0 * unit(rng);
        out.emplace_back(150.0 + noise(rng), n, 25.0 + 4.0 * (n / 120.0) * (n / 120.0));
      }
    }
    if (pole) {
      for (int k = 0; k < 80; ++k) {
        const double a = M_PI * unit(rng);
        out.emplace_back(50.0 - 0.2 * std::sin(a), 40.0 + 0.2 * std::cos(a), 30.0 * unit(rng));
      }
    }
    if (tree) {
      for (int k = 0; k < 150; ++k) {
        const double a = 2.0 * M_PI * unit(rng), r = 3.0 * std::sqrt(unit(rng));
        out.emplace_back(250.0 + r * std::cos(a), -70.0 + r * std::sin(a), 3.0 + 9.0 * unit(rng));
      }
    }
    for (int k = 0; k < 3; ++k) {
      out.emplace_back(-400.0 + 800.0 * unit(rng), -300.0 + 600.0 * unit(rng), 200.0 * unit(rng));
    }
    return out;
  }
};

constexpr double kPeriodS = 0.25;  // exact in binary: hold_s's comparisons are exact too

std::vector<ObstacleWarning> fly(ObstacleDetector& detector, const SyntheticScene& scene,
                                 std::int64_t frame) {
  const std::vector<Eigen::Vector3d> returns = scene.frame(static_cast<std::uint64_t>(frame) + 11);
  DetectorFrame input;
  input.frame = frame;
  input.time_s = static_cast<double>(frame) * kPeriodS;
  input.aircraft_enu_m = Eigen::Vector3d(-400.0, 0.0, 60.0);
  input.returns_enu_m = returns;
  const std::span<const ObstacleWarning> warnings = detector.add_frame(input);
  return {warnings.begin(), warnings.end()};
}

const ObstacleWarning* warning_near(const std::vector<ObstacleWarning>& warnings, double e, double n,
                                    double within) {
  for (const ObstacleWarning& w : warnings) {
    if (std::hypot(w.nearest_enu_m.x() - e, w.nearest_enu_m.y() - n) <= within) return &w;
  }
  return nullptr;
}

TEST(ObstacleDetector, ClassesTracksAndHoldsASyntheticScene) {
  ObstacleDetector detector(DetectorParams{}, kPeriodS);
  SyntheticScene scene;
  std::vector<ObstacleWarning> warnings;
  for (std::int64_t f = 0; f < 6; ++f) warnings = fly(detector, scene, f);
  ASSERT_EQ(warnings.size(), 3u) << "wire, pole and tree, nothing else";
  const ObstacleWarning* wire = warning_near(warnings, 150.0, 0.0, 10.0);
  const ObstacleWarning* pole = warning_near(warnings, 50.0, 40.0, 1.0);
  const ObstacleWarning* tree = warning_near(warnings, 250.0, -70.0, 4.0);
  ASSERT_TRUE(wire && pole && tree);
  EXPECT_EQ(wire->kind, ObstacleClass::wire);
  EXPECT_EQ(pole->kind, ObstacleClass::pole);
  EXPECT_EQ(tree->kind, ObstacleClass::tree);
  EXPECT_NEAR(pole->height_m, 30.0, 0.5);
  EXPECT_NEAR(tree->height_m, 12.0, 0.5);
  EXPECT_GT(wire->length_m, 200.0);
  EXPECT_NEAR(wire->nearest_enu_m.z(), 25.0, 0.5);
  // The nearest point is the nearest to the aircraft of what was seen: the pole's at its foot.
  EXPECT_NEAR(pole->range_m, (pole->nearest_enu_m - Eigen::Vector3d(-400, 0, 60)).norm(), 1e-9);
  const std::int64_t wire_track = wire->track, pole_track = pole->track;

  // The tracks keep their ids while re-detected.
  for (std::int64_t f = 6; f < 12; ++f) warnings = fly(detector, scene, f);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(warning_near(warnings, 150.0, 0.0, 10.0)->track, wire_track);
  EXPECT_EQ(warning_near(warnings, 50.0, 40.0, 1.0)->track, pole_track);

  // Gone from the returns: supported while the window (1 s, 4 frames) holds its points, then
  // held without support (points 0) for hold_s = 2 s, then dropped.
  scene.pole = false;
  int supported = 0, held = 0;
  for (std::int64_t f = 12; f < 40; ++f) {
    warnings = fly(detector, scene, f);
    const ObstacleWarning* w = warning_near(warnings, 50.0, 40.0, 1.0);
    if (w == nullptr) break;
    EXPECT_EQ(w->track, pole_track);
    ++(w->points > 0 ? supported : held);
    if (w->points > 0) EXPECT_EQ(held, 0);
  }
  EXPECT_EQ(supported, 3) << "frames 9, 10 and 11 in the window";
  EXPECT_EQ(held, 8) << "2 s of 0.25 s frames";
  EXPECT_EQ(warning_near(warnings, 50.0, 40.0, 1.0), nullptr);
  EXPECT_NE(warning_near(warnings, 150.0, 0.0, 10.0), nullptr);
}

TEST(ObstacleDetector, TheSameFramesGiveTheSameWarningsBitForBit) {
  const auto run = [] {
    ObstacleDetector detector(DetectorParams{}, kPeriodS);
    std::vector<ObstacleWarning> all;
    for (std::int64_t f = 0; f < 8; ++f) {
      const std::vector<ObstacleWarning> w = fly(detector, SyntheticScene{}, f);
      all.insert(all.end(), w.begin(), w.end());
    }
    return all;
  };
  const std::vector<ObstacleWarning> a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 10u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].track, b[k].track);
    EXPECT_EQ(a[k].kind, b[k].kind);
    EXPECT_EQ(a[k].nearest_enu_m, b[k].nearest_enu_m);
    EXPECT_EQ(a[k].length_m, b[k].length_m);
    EXPECT_EQ(a[k].height_m, b[k].height_m);
  }
}

TEST(ObstacleDetector, GroundAndFalseReturnsAloneWarnOfNothing) {
  ObstacleDetector detector(DetectorParams{}, kPeriodS);
  SyntheticScene scene{.wire = false, .pole = false, .tree = false};
  for (std::int64_t f = 0; f < 30; ++f) EXPECT_TRUE(fly(detector, scene, f).empty()) << f;
}

TEST(ObstacleDetector, RefusesBadParameters) {
  DetectorParams p;
  p.window_s = 0.0;
  EXPECT_THROW(ObstacleDetector detector(p, kPeriodS), Error);
  p = {};
  p.min_points = 1;
  try {
    ObstacleDetector detector(p, kPeriodS);
    FAIL();
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "detector: min_points: must be in [2, 100000], got 1");
  }
  EXPECT_THROW(ObstacleDetector detector(DetectorParams{}, 0.0), Error);
}

TEST(DetectorKeys, TheirRangesAreTheScenarioTablesRows) {
  for (const DetectorKey& key : detector_keys()) {
    SCOPED_TRACE(std::string(key.name));
    const ValueRange* range = value_range_of("detector." + std::string(key.name));
    ASSERT_NE(range, nullptr);
    EXPECT_EQ(range->min, key.min);
    EXPECT_EQ(range->max, key.max);
    EXPECT_EQ(range->unit, key.unit);
    // The default lies in its range.
    DetectorParams defaults;
    const double value = key.number ? defaults.*key.number : defaults.min_points;
    EXPECT_GE(value, key.min);
    EXPECT_LE(value, key.max);
  }
  EXPECT_TRUE(detector_param_problems(DetectorParams{}).empty());
}

}  // namespace
}  // namespace owsim
