// Protects the world frame of SENSOR-SPEC §4 "Decision (world frame)": exact local ENU on WGS-84
// around the scenario origin, checked against pyproj (an independent ECEF implementation).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <GeographicLib/Geodesic.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

using test::python_number;
using test::run_python;

const Geodetic kOrigin{48.6881, 10.8447, 450.0};  // the INTERFACE.md example origin

TEST(LocalFrame, OriginMapsToZero) {
  const LocalFrame frame(kOrigin);
  const Eigen::Vector3d enu = frame.enu_from_geodetic(kOrigin);
  EXPECT_NEAR(enu.norm(), 0.0, 1e-9);
  EXPECT_EQ(frame.origin().lat_deg, kOrigin.lat_deg);
  const Geodetic back = frame.geodetic_from_enu(Eigen::Vector3d::Zero());
  EXPECT_NEAR(back.lat_deg, kOrigin.lat_deg, 1e-12);
  EXPECT_NEAR(back.lon_deg, kOrigin.lon_deg, 1e-12);
  EXPECT_NEAR(back.h_m, kOrigin.h_m, 1e-9);
}

TEST(LocalFrame, RoundTripWithin50Km) {
  const LocalFrame frame(kOrigin);
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> horizontal(-50'000.0, 50'000.0), up(-500.0, 9'000.0);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d enu(horizontal(rng), horizontal(rng), up(rng));
    const Eigen::Vector3d back = frame.enu_from_geodetic(frame.geodetic_from_enu(enu));
    // Via ECEF, where one ulp of a coordinate (~6.4e6 m) is 0.9 nm: the round trip is good to a
    // few ulps (3.1 nm worst over these points), so 1e-9 m itself is below double precision.
    EXPECT_LT((back - enu).norm(), 1e-8) << enu.transpose();
  }
}

TEST(LocalFrame, OneKilometreNorthAlongTheEllipsoid) {
  // On the ellipsoid (h = 0), so the geodesic's 1000 m is the arc length of the point's path.
  const Geodetic origin{kOrigin.lat_deg, kOrigin.lon_deg, 0.0};
  const LocalFrame frame(origin);
  double lat2 = 0, lon2 = 0;
  GeographicLib::Geodesic::WGS84().Direct(origin.lat_deg, origin.lon_deg, 0.0, 1000.0, lat2, lon2);
  const Eigen::Vector3d enu = frame.enu_from_geodetic({lat2, lon2, 0.0});
  EXPECT_NEAR(enu.x(), 0.0, 1e-9);
  EXPECT_NEAR(enu.y(), 1000.0, 1e-3);  // the chord is shorter than the arc by s³/(8M²) ≈ 3 µm
  // The surface drops below the tangent plane by s²/(2M), M the meridian radius of curvature.
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double sin_lat = std::sin(origin.lat_deg * std::numbers::pi / 180.0);
  const double meridian_radius_m = a * (1 - e2) / std::pow(1 - e2 * sin_lat * sin_lat, 1.5);
  EXPECT_NEAR(enu.z(), -1000.0 * 1000.0 / (2 * meridian_radius_m), 1e-6);
  EXPECT_NEAR(enu.z(), -0.0785, 5e-4);
}

TEST(LocalFrame, AgreesWithPyprojEcef) {
  const LocalFrame frame(kOrigin);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> dlat(-0.4, 0.4), dlon(-0.6, 0.6), h(-500.0, 9000.0);
  std::vector<Geodetic> points;
  for (int i = 0; i < 20; ++i) {
    points.push_back({kOrigin.lat_deg + dlat(rng), kOrigin.lon_deg + dlon(rng), h(rng)});
  }
  std::ostringstream script;
  script << "import numpy as np\n"
            "from pyproj import Transformer\n"
            "t = Transformer.from_crs('EPSG:4979', 'EPSG:4978', always_xy=True)\n"
            "lat0, lon0, h0 = "
         << python_number(kOrigin.lat_deg) << ", " << python_number(kOrigin.lon_deg) << ", "
         << python_number(kOrigin.h_m)
         << "\n"
            "p0 = np.array(t.transform(lon0, lat0, h0))\n"
            "f, l = np.radians(lat0), np.radians(lon0)\n"
            "R = np.array([[-np.sin(l), np.cos(l), 0],\n"
            "              [-np.sin(f)*np.cos(l), -np.sin(f)*np.sin(l), np.cos(f)],\n"
            "              [np.cos(f)*np.cos(l), np.cos(f)*np.sin(l), np.sin(f)]])\n"
            "pts = [";
  for (const Geodetic& p : points) {
    script << "(" << python_number(p.lat_deg) << ", " << python_number(p.lon_deg) << ", "
           << python_number(p.h_m) << "),";
  }
  script << "]\n"
            "for lat, lon, h in pts:\n"
            "    enu = R @ (np.array(t.transform(lon, lat, h)) - p0)\n"
            "    print('%.17g %.17g %.17g' % tuple(enu))\n";
  std::istringstream output(run_python(script.str()));
  for (const Geodetic& p : points) {
    Eigen::Vector3d expected;
    ASSERT_TRUE(output >> expected.x() >> expected.y() >> expected.z());
    const Eigen::Vector3d enu = frame.enu_from_geodetic(p);
    EXPECT_LT((enu - expected).norm(), 1e-6) << p.lat_deg << " " << p.lon_deg << " " << p.h_m;
  }
}

TEST(LocalFrame, LocalLevelRotationAgreesWithPyproj) {
  const LocalFrame frame(kOrigin);
  const std::vector<Eigen::Vector3d> positions = {
      {0, 0, 0}, {20'000, 0, 500}, {0, -30'000, 2'000}, {-15'000, 25'000, 100}};
  std::ostringstream script;
  script << "import numpy as np\n"
            "from pyproj import Transformer\n"
            "def R(lat, lon):\n"
            "    f, l = np.radians(lat), np.radians(lon)\n"
            "    return np.array([[-np.sin(l), np.cos(l), 0],\n"
            "                     [-np.sin(f)*np.cos(l), -np.sin(f)*np.sin(l), np.cos(f)],\n"
            "                     [np.cos(f)*np.cos(l), np.cos(f)*np.sin(l), np.sin(f)]])\n"
            "M0 = R("
         << python_number(kOrigin.lat_deg) << ", " << python_number(kOrigin.lon_deg) << ")\n";
  for (const Eigen::Vector3d& position : positions) {
    const Geodetic g = frame.geodetic_from_enu(position);
    script << "print(' '.join('%.17g' % v for v in (M0 @ R(" << python_number(g.lat_deg) << ", "
           << python_number(g.lon_deg) << ").T).flatten()))\n";
  }
  std::istringstream output(run_python(script.str()));
  for (const Eigen::Vector3d& position : positions) {
    Eigen::Matrix3d expected;
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) ASSERT_TRUE(output >> expected(row, col));
    }
    const Eigen::Matrix3d m = frame.enu_rotation_at(position);
    EXPECT_LT((m - expected).norm(), 1e-12) << position.transpose();
    EXPECT_NEAR(m.determinant(), 1.0, 1e-14);
  }
  // 20 km east the local vertical leans east by ~20/6380 rad ≈ 0.18°.
  const Eigen::Vector3d local_up = frame.enu_rotation_at({20'000, 0, 500}).col(2);
  EXPECT_NEAR(std::asin(local_up.x()) * 180.0 / std::numbers::pi, 0.18, 0.01);
}

// origin_of_frame inverts the frame for its origin: from a point given both ways (geodetic and
// local), the true origin comes back, over random origins and points up to 30 km away.
TEST(LocalFrame, OriginOfFrameRecoversTheOrigin) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> lat(-80, 80), lon(-180, 180), h(-100, 3000),
      horizontal(-30'000, 30'000), up(-3'000, 3'000);
  for (int i = 0; i < 200; ++i) {
    const Geodetic origin{lat(random), lon(random), h(random)};
    const LocalFrame frame(origin);
    const Eigen::Vector3d enu(horizontal(random), horizontal(random), up(random));
    const Geodetic point = frame.geodetic_from_enu(enu);
    const Geodetic found = origin_of_frame(point, enu);
    EXPECT_NEAR(found.lat_deg, origin.lat_deg, 1e-10) << i;
    EXPECT_NEAR(found.lon_deg, origin.lon_deg, 1e-10) << i;
    EXPECT_NEAR(found.h_m, origin.h_m, 1e-5) << i;
    EXPECT_LT((LocalFrame(found).enu_from_geodetic(point) - enu).norm(), 1e-5) << i;
  }
  EXPECT_THROW((void)origin_of_frame({0, 0, 0}, Eigen::Vector3d(NAN, 0, 0)), Error);
}

TEST(LocalFrame, RejectsOriginsOutOfRange) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(LocalFrame({90.5, 0, 0}), Error);
  EXPECT_THROW(LocalFrame({-91, 0, 0}), Error);
  EXPECT_THROW(LocalFrame({nan, 0, 0}), Error);
  EXPECT_THROW(LocalFrame({0, 540, 0}), Error);
  EXPECT_THROW(LocalFrame({0, -541, 0}), Error);
  EXPECT_THROW(LocalFrame({0, 0, nan}), Error);
  EXPECT_THROW(LocalFrame({0, 0, std::numeric_limits<double>::infinity()}), Error);
  EXPECT_NO_THROW(LocalFrame({90, -540, -100}));
  try {
    LocalFrame({95, 0, 0});
    FAIL() << "no throw";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("local frame origin: latitude 95° is outside"),
              std::string::npos)
        << error.what();
  }
  const LocalFrame frame(kOrigin);
  EXPECT_THROW((void)frame.enu_from_geodetic({100, 0, 0}), Error);
}

TEST(LocalFrame, LongitudeBeyond180IsTheSamePlace) {
  const LocalFrame a({48.0, 10.0, 0}), b({48.0, 370.0, 0});
  const Geodetic p{48.01, 10.02, 30};
  EXPECT_LT((a.enu_from_geodetic(p) - b.enu_from_geodetic(p)).norm(), 1e-8);
}

}  // namespace
}  // namespace owsim
