// Protects the points' geodesy (geometry/geodesy_cells.hpp, docs/model.md "Geodesy of the
// points"): every return of frames of every bundled example, and points all around the real
// recorded flight, placed by the cubes' expansions within 10 nm of GeographicLib in lat, lon, h
// and the LAS grid's easting and northing; exact at a cube's centre; the same wherever and in
// whatever order a point comes; the exact path where an expansion cannot hold (the antimeridian,
// the poles, a grid's edge); and the printed digits at most one unit off the exact ones.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "geometry/geodesy_cells.hpp"
#include "geometry/utm.hpp"
#include "io/files/csv_cells.hpp"
#include "io/trajectory/ardupilot_log_reader.hpp"
#include "owsim/owsim.hpp"

namespace owsim {
namespace {

constexpr double kMetresPerDegree = 111'320.0;

struct Worst {
  double metres = 0;  // the largest position error: lat/lon at 111.32 km a degree, h, E, N
  long points = 0;
  long off_by_one = 0;  // printed lat/lon (9 decimals) or h (4) one unit from the exact text
};

double printed(double value, int decimals) {
  std::array<char, kCsvNumberMaxChars> text{};
  char* end = write_csv_fixed(text.data(), value, decimals);
  return std::stod(std::string(text.data(), end));
}

// Places `enu` both ways and folds the difference into `worst`; fails on more than one unit in
// the last printed digit.
void compare(const GeodesyCells& cells, GeodesyCells::Cursor& cursor, const Eigen::Vector3d& enu,
             Worst& worst) {
  const PlacedPoint fast = cells.place(enu, cursor);
  const PlacedPoint exact = cells.place_exactly(enu);
  double error =
      std::max({std::abs(fast.geodetic.lat_deg - exact.geodetic.lat_deg) * kMetresPerDegree,
                std::abs(fast.geodetic.lon_deg - exact.geodetic.lon_deg) * kMetresPerDegree,
                std::abs(fast.geodetic.h_m - exact.geodetic.h_m)});
  if (cells.grid()) error = std::max(error, (fast.grid_m - exact.grid_m).cwiseAbs().maxCoeff());
  worst.metres = std::max(worst.metres, error);
  ++worst.points;
  const double lat =
      std::abs(printed(fast.geodetic.lat_deg, 9) - printed(exact.geodetic.lat_deg, 9));
  const double lon =
      std::abs(printed(fast.geodetic.lon_deg, 9) - printed(exact.geodetic.lon_deg, 9));
  const double h = std::abs(printed(fast.geodetic.h_m, 4) - printed(exact.geodetic.h_m, 4));
  if (lat > 0 || lon > 0 || h > 0) ++worst.off_by_one;
  ASSERT_LE(lat, 1.5e-9) << enu.transpose();
  ASSERT_LE(lon, 1.5e-9) << enu.transpose();
  ASSERT_LE(h, 1.5e-4) << enu.transpose();
}

// Every return of three frames (first, middle, last) of every bundled example, placed with the
// grid points.las of that scenario uses.
TEST(GeodesyCells, EveryExamplesReturnsWithinTenNanometres) {
  const std::filesystem::path examples = std::filesystem::path(OWSIM_SOURCE_DIR) / "examples";
  for (const char* name :
       {"single_span", "pylon_line", "corridor", "hellsim_flight", "fog_bank", "real_corridor"}) {
    const Simulation sim = Simulation::open(examples / (std::string(name) + ".yaml"));
    const Geodetic origin = sim.scenario().origin;
    const GeodesyCells cells{LocalFrame(origin), utm_grid_of(origin)};
    GeodesyCells::Cursor cursor;
    Worst worst;
    Frame frame;
    for (const std::int64_t k : {std::int64_t{0}, sim.frame_count() / 2, sim.frame_count() - 1}) {
      sim.simulate_frame(k, frame);
      for (const ReturnRecord& r : frame.returns()) {
        compare(cells, cursor, {r.e_m, r.n_m, r.u_m}, worst);
        // The embedding API's returns are placed the same way.
        const PlacedPoint fast = cells.place({r.e_m, r.n_m, r.u_m}, cursor);
        ASSERT_EQ(r.lat_deg, fast.geodetic.lat_deg);
        ASSERT_EQ(r.h_m, fast.geodetic.h_m);
      }
    }
    EXPECT_GT(worst.points, 1000) << name;
    EXPECT_LT(worst.metres, kGeodesyCellToleranceM) << name;
    // Off by one digit only where the exact value lies within ~1 nm of a rounding edge.
    EXPECT_LT(worst.off_by_one, worst.points / 2000 + 2) << name;
    RecordProperty(std::string(name) + "_worst_nm", std::to_string(worst.metres * 1e9));
  }
}

// The real recorded flight (Oslo, 59.96°N, UTM zone 32 near its edge): random points within the
// sensor's reach (1.3 km) of every 10th navigation record.
TEST(GeodesyCells, AroundTheRealFlightWithinTenNanometres) {
  const std::string log_path = std::string(OWSIM_SHARED_DIR) + "/data/real/WingFlight1.log";
  if (!std::filesystem::exists(log_path)) GTEST_SKIP() << log_path << " is not here";
  const ArduPilotLog log = read_ardupilot_log(log_path);
  const Geodetic origin = log.records.front().position;
  const LocalFrame frame(origin);
  const GeodesyCells cells{frame, utm_grid_of(origin)};
  GeodesyCells::Cursor cursor;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Worst worst;
  for (std::size_t i = 0; i < log.records.size(); i += 10) {
    const Eigen::Vector3d aircraft = frame.enu_from_geodetic(log.records[i].position);
    for (int j = 0; j < 200; ++j) {
      Eigen::Vector3d offset(unit(random), unit(random), unit(random));
      if (offset.norm() > 1.0) continue;
      compare(cells, cursor, aircraft + 1300.0 * offset, worst);
    }
  }
  EXPECT_GT(worst.points, 10'000);
  EXPECT_LT(worst.metres, kGeodesyCellToleranceM);
  EXPECT_LT(worst.off_by_one, worst.points / 2000 + 2);
}

TEST(GeodesyCells, ExactAtTheCentreAndTheSameInAnyOrder) {
  const Geodetic origin{48.6881, 10.8447, 450.0};
  const GeodesyCells cells{LocalFrame(origin), utm_grid_of(origin)};
  GeodesyCells::Cursor cursor;
  const Eigen::Vector3d centre(1500.0, -500.0, 500.0);  // the centre of cube (1, −1, 0)
  const PlacedPoint fast = cells.place(centre, cursor);
  const PlacedPoint exact = cells.place_exactly(centre);
  EXPECT_EQ(fast.geodetic.lat_deg, exact.geodetic.lat_deg);
  EXPECT_EQ(fast.geodetic.lon_deg, exact.geodetic.lon_deg);
  EXPECT_EQ(fast.geodetic.h_m, exact.geodetic.h_m);
  EXPECT_EQ(fast.grid_m, exact.grid_m);
  // Another GeodesyCells, another cursor, the points in reverse: bit for bit the same.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(-3000.0, 3000.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) points.emplace_back(u(random), u(random), u(random) / 10);
  std::vector<PlacedPoint> forward;
  for (const Eigen::Vector3d& p : points) forward.push_back(cells.place(p, cursor));
  const GeodesyCells again{LocalFrame(origin), utm_grid_of(origin)};
  const GeodesyCells no_grid{LocalFrame(origin)};
  GeodesyCells::Cursor other, third;
  for (std::size_t i = points.size(); i-- > 0;) {
    const PlacedPoint back = again.place(points[i], other);
    EXPECT_EQ(back.geodetic.lat_deg, forward[i].geodetic.lat_deg);
    EXPECT_EQ(back.geodetic.lon_deg, forward[i].geodetic.lon_deg);
    EXPECT_EQ(back.grid_m, forward[i].grid_m);
    // Without a grid: the same lat/lon/h (points.csv alone equals points.csv beside points.las).
    const PlacedPoint plain = no_grid.place(points[i], third);
    EXPECT_EQ(plain.geodetic.lat_deg, forward[i].geodetic.lat_deg);
    EXPECT_EQ(plain.geodetic.h_m, forward[i].geodetic.h_m);
    EXPECT_TRUE(plain.grid_m.hasNaN());
  }
}

// Where no expansion can hold, the exact path: at the pole (longitude turns all the way round
// within a cube). Across the antimeridian GeographicLib's longitudes run on past 180° in the
// cube, smooth, so the expansion holds there and agrees. The grid's edge gives NaN grid
// positions (the LAS writer then names the point).
TEST(GeodesyCells, ExactPathWhereTheExpansionCannotHold) {
  {
    const GeodesyCells cells{LocalFrame(Geodetic{89.9995, 0.0, 0.0})};
    GeodesyCells::Cursor cursor;
    for (const Eigen::Vector3d p :
         {Eigen::Vector3d(20.0, 30.0, 0.0), Eigen::Vector3d(-40.0, 70.0, 5.0)}) {
      EXPECT_EQ(cells.cell_error_m(p), 0.0);  // the cube took the exact path
      const PlacedPoint fast = cells.place(p, cursor);
      const PlacedPoint exact = cells.place_exactly(p);
      EXPECT_EQ(fast.geodetic.lat_deg, exact.geodetic.lat_deg);
      EXPECT_EQ(fast.geodetic.lon_deg, exact.geodetic.lon_deg);
    }
  }
  {
    const GeodesyCells cells{LocalFrame(Geodetic{10.0, 179.9995, 0.0})};
    GeodesyCells::Cursor cursor;
    Worst worst;
    for (double e = -900.0; e < 1000.0; e += 37.0) compare(cells, cursor, {e, 100.0, 0.0}, worst);
    EXPECT_LT(worst.metres, kGeodesyCellToleranceM);
  }
  // UTM zone 32's grid far to the west, where GeographicLib refuses the forced zone.
  const Geodetic origin{0.0, 9.0, 0.0};
  const GeodesyCells cells{LocalFrame(origin), UtmGrid{32, true}};
  GeodesyCells::Cursor cursor;
  EXPECT_TRUE(cells.place({0, 0, 0}, cursor).grid_m.allFinite());
  EXPECT_TRUE(cells.place({-6'000'000.0, 0.0, -3'000'000.0}, cursor).grid_m.hasNaN());
  EXPECT_GT(cells.cell_error_m({100, 100, 0}), 0.0);  // a fitted cube, its check error
  EXPECT_LT(cells.cell_error_m({100, 100, 0}), kGeodesyCellToleranceM);
}

}  // namespace
}  // namespace owsim
