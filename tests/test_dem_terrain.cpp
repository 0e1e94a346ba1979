// Protects DEM terrain (geometry/post_lattice.hpp, io/scenario/dem_terrain.hpp): the lattice's
// surface, holes and edges against closed forms, and whole runs over GeoTIFFs that GDAL writes
// (a projected and a geographic CRS, each with a NODATA patch) against GDAL's own bilinear
// interpolation of the raster at every ground return's latitude and longitude
// (tests/oracles/dem_oracle.py); bad DEMs give one line and no output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <string>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/post_lattice.hpp"
#include "io/scenario/dem_terrain.hpp"
#include "python_oracle.hpp"
#include "scene_fixtures.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

// A lattice rotated by `angle` with posts on the plane u = 3 + 0.2 e − 0.1 n (any triangulation
// of a plane is the plane), raster row 0 the northmost.
PostLattice plane_lattice(double angle, int ncols, int nrows, double step_m) {
  PostLattice lattice;
  lattice.ncols = ncols;
  lattice.nrows = nrows;
  const Eigen::Vector2d along(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d down(std::sin(angle), -std::cos(angle));
  for (int r = 0; r < nrows; ++r) {
    for (int c = 0; c < ncols; ++c) {
      const Eigen::Vector2d en = (c * along + r * down) * step_m;
      lattice.posts.emplace_back(en.x(), en.y(), 3.0 + 0.2 * en.x() - 0.1 * en.y());
      lattice.valid.push_back(1);
    }
  }
  return lattice;
}

TEST(PostLattice, HeightIsTheSurfaceAtRandomPoints) {
  test::Rng rng(20);
  for (double angle : {0.0, 0.3, -1.1}) {
    const PostLattice lattice = plane_lattice(angle, 40, 30, 10.0);
    lattice.validate("plane");
    for (int i = 0; i < 500; ++i) {
      const double c = test::uniform(rng, 0.0, 39.0), r = test::uniform(rng, 0.0, 29.0);
      const Eigen::Vector2d en = (c * Eigen::Vector2d(std::cos(angle), std::sin(angle)) +
                                  r * Eigen::Vector2d(std::sin(angle), -std::cos(angle))) *
                                 10.0;
      EXPECT_NEAR(lattice.height_at(en.x(), en.y()), 3.0 + 0.2 * en.x() - 0.1 * en.y(), 1e-9);
      EXPECT_TRUE(lattice.covers(en.x(), en.y()));
    }
    EXPECT_FALSE(lattice.covers(-50.0 * std::cos(angle), -50.0 * std::sin(angle)));
    EXPECT_THROW((void)lattice.height_at(-50.0 * std::cos(angle), -50.0 * std::sin(angle)), Error);
  }
}

TEST(PostLattice, TwistedCellFollowsItsTwoTriangles) {
  // One 10 m cell, heights 0 except its north-west post at 4 m: the diagonal runs from the
  // south-west post (row 1, col 0) to the north-east one (row 0, col 1).
  PostLattice lattice;
  lattice.ncols = 2;
  lattice.nrows = 2;
  lattice.posts = {{0, 10, 4}, {10, 10, 0}, {0, 0, 0}, {10, 0, 0}};
  lattice.valid = {1, 1, 1, 1};
  EXPECT_NEAR(lattice.height_at(5.0, 5.0), 0.0, 1e-12);  // on the diagonal
  EXPECT_NEAR(lattice.height_at(2.0, 7.0), 2.0, 1e-12);  // north-west triangle: −0.4 e + 0.4 n
  EXPECT_NEAR(lattice.height_at(7.0, 2.0), 0.0, 1e-12);  // south-east triangle is flat
  const TriangleMesh mesh =
      lattice.mesh(Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    EXPECT_GT((b - a).cross(c - a).z(), 0.0);  // counter-clockwise seen from above
  }
}

TEST(PostLattice, HolesAreNoSurface) {
  PostLattice lattice = plane_lattice(0.0, 5, 5, 10.0);
  lattice.valid[lattice.index(2, 2)] = 0;  // the four cells around post (2, 2)
  EXPECT_EQ(
      lattice.mesh(Eigen::AlignedBox2d(Eigen::Vector2d(-100, -100), Eigen::Vector2d(100, 100)))
          .triangles.size(),
      2u * (16 - 4));
  EXPECT_TRUE(lattice.covers(20.0, -20.0));
  EXPECT_FALSE(lattice.height_if_any(21.0, -19.0).has_value());
  EXPECT_THROW((void)lattice.height_at(21.0, -19.0), Error);
  EXPECT_NEAR(lattice.height_at(5.0, -5.0), 3.0 + 1.0 + 0.5, 1e-9);
  lattice.posts.pop_back();
  EXPECT_THROW(lattice.validate("short"), Error);
}

class DemRuns : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path oracle = fs::path(OWSIM_SOURCE_DIR) / "tests/oracles/dem_oracle.py";
    (void)test::run_python_file(oracle,
                                {"make " + dir_.path().string() + " 48.6881 10.8447", false});
  }

  // The single-span example over the DEM `file`, flying from `east_m` at 110 m.
  CliResult run(const std::string& file, const std::string& out, double east_m = 200.0) {
    std::ifstream example(fs::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml");
    std::string yaml((std::istreambuf_iterator<char>(example)), std::istreambuf_iterator<char>());
    const auto replace = [&yaml](const std::string& from, const std::string& to) {
      const auto at = yaml.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      yaml.replace(at, from.size(), to);
    };
    replace("terrain: {flat_u: 0}", "terrain: {dem: " + file + "}");
    replace("{e: -600, n: 0, u: 60}", "{e: -600, n: 0, u: 110}");
    replace("{e: 200, n: 0, u: 60}", "{e: " + std::to_string(east_m) + ", n: 0, u: 110}");
    const fs::path scenario = dir_ / (out + ".yaml");
    std::ofstream(scenario) << yaml;
    return run_cli({"run", scenario.string(), "--no-noise", "--frames", "6", "--outputs",
                    "points,summary", "--out", (dir_ / out).string()},
                   dir_.path());
  }

  std::string check(const std::string& out, const std::string& raster) {
    const fs::path oracle = fs::path(OWSIM_SOURCE_DIR) / "tests/oracles/dem_oracle.py";
    return test::run_python_file(
        oracle,
        {"check " + (dir_ / out / "points.csv").string() + " " + (dir_ / raster).string(), false});
  }

  // Runs over the DEM `raster` into `out` and checks every ground return with the oracle.
  void expect_ground_on(const std::string& raster, const std::string& out) {
    const CliResult result = run(raster, out);
    ASSERT_EQ(result.exit_status, 0) << result.err;
    const std::string verdict = check(out, raster);
    ASSERT_EQ(verdict.rfind("ok ", 0), 0u) << verdict;
    EXPECT_GT(std::stol(verdict.substr(3)), 10000) << verdict;
  }

  TempDir dir_{"owsim_dem"};
};

TEST_F(DemRuns, GroundReturnsLieOnTheProjectedDem) { expect_ground_on("utm.tif", "utm"); }

TEST_F(DemRuns, GroundReturnsLieOnTheGeographicDem) { expect_ground_on("geo.tif", "geo"); }

// A recorded trajectory (CSV, east along n = 0 at 110 m) over the DEM `file`, from e0 to e1.
CliResult recorded_run(const TempDir& dir, const std::string& file, double e0_m, double e1_m) {
  std::ofstream track(dir / "track.csv");
  track << "time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg,heading_deg\n";
  const double metres_per_deg_lon = 111'320.0 * std::cos(48.6881 * M_PI / 180.0);
  for (int i = 0; i <= 200; ++i) {
    const double e = e0_m + (e1_m - e0_m) * i / 200.0;
    track << std::setprecision(12) << 0.1 * i << ",48.6881," << 10.8447 + e / metres_per_deg_lon
          << ",560,0,0,90\n";
  }
  track.close();
  std::ofstream(dir / "recorded.yaml")
      << "name: recorded\norigin: {lat: 48.6881, lon: 10.8447, h: 450.0}\n"
         "trajectory: {file: track.csv, format: csv}\n"
         "scene:\n  terrain: {dem: "
      << file << "}\n";
  return run_cli({"run", (dir / "recorded.yaml").string(), "--no-noise", "--frames", "4",
                  "--outputs", "points,summary", "--out", (dir / "recorded").string()},
                 dir.path());
}

// EGM96 heights (a compound CRS, UTM + EPSG:5773) are turned into ellipsoidal heights with PROJ's
// geoid grid: ~47 m apart here, so a DEM taken as ellipsoidal would miss the oracle by that.
TEST_F(DemRuns, GeoidHeightsAreConvertedToEllipsoidalHeights) {
  expect_ground_on("egm96.tif", "egm96");
}

TEST_F(DemRuns, RecordedFlightsReadTheirReachAndMustLieOnTheDem) {
  const CliResult result = recorded_run(dir_, "utm.tif", -600.0, 200.0);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const std::string verdict = check("recorded", "utm.tif");
  ASSERT_EQ(verdict.rfind("ok ", 0), 0u) << verdict;
  fs::remove_all(dir_ / "recorded");
  const CliResult off = recorded_run(dir_, "utm.tif", 1500.0, 3500.0);
  EXPECT_NE(off.exit_status, 0);
  EXPECT_NE(off.err.find("does not cover the flight"), std::string::npos) << off.err;
  EXPECT_FALSE(fs::exists(dir_ / "recorded"));
}

// A VRT whose raw band is /etc/passwd: GDAL would read the system file as heights.
void write_hostile_vrt(const fs::path& file) {
  std::ofstream(file) << R"(<VRTDataset rasterXSize="10" rasterYSize="10"><SRS>EPSG:4326</SRS>
<GeoTransform>10.84,0.001,0,48.69,0,-0.001</GeoTransform>
<VRTRasterBand dataType="Byte" band="1" subClass="VRTRawRasterBand">
<SourceFilename relativetoVRT="0">/etc/passwd</SourceFilename></VRTRasterBand></VRTDataset>
)";
}

TEST_F(DemRuns, BadDemsGiveOneLineAndNoOutput) {
  write_hostile_vrt(dir_ / "passwd.vrt");
  fs::create_symlink("/dev/zero", dir_ / "zero.tif");
  fs::create_symlink("loop.tif", dir_ / "loop.tif");
  // An ASCII grid whose header claims 10^6 × 10^6 millimetre cells around the flight, in 80 bytes.
  std::ofstream(dir_ / "huge.asc") << "ncols 1000000\nnrows 1000000\nxllcorner 635263.5\n"
                                      "yllcorner 5393926.2\ncellsize 0.001\nNODATA_value -9999\n"
                                      "1 2 3 4\n";
  fs::copy_file(fs::path(OWSIM_SOURCE_DIR) / "examples/data/real_corridor_dem.prj",
                dir_ / "huge.prj");  // UTM zone 32N
  const struct {
    std::string file;
    double east_m;
    std::string says;
  } cases[] = {{"nocrs.tif", 200.0, "declares no CRS"},
               {"missing.tif", 200.0, "no such file: "},
               {"utm.tif", 2800.0, "does not cover the flight"},
               // Issue 33: nothing but local regular files in the scenario's folder tree, and no
               // format that names other files.
               {"/vsicurl/http://127.0.0.1:9/x.tif", 200.0, "a GDAL virtual file system"},
               {"http://127.0.0.1:9/x.tif", 200.0, "a URL or a connection string"},
               {"'WMS:http://127.0.0.1:9/?'", 200.0, "a URL or a connection string"},
               {"passwd.vrt", 200.0, "a VRT file, which terrain.dem does not accept"},
               {"/etc/passwd", 200.0, "outside the folder"},
               {"../utm.tif", 200.0, "outside the folder"},
               {"zero.tif", 200.0, "outside the folder"},
               {"loop.tif", 200.0, "a symbolic link loop"},
               // Issue 33, family 4: refused before anything is allocated for it.
               {"huge.asc", 200.0,
                "is 1000000 × 1000000 posts, about 64000 GB at 64 bytes a post, more than this "
                "machine's"}};
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.file);
    const CliResult result = run(bad.file, "bad", bad.east_m);
    EXPECT_NE(result.exit_status, 0);
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find("scene.terrain.dem"), std::string::npos) << result.err;
    const std::string named = bad.file.front() == '\'' ? bad.file.substr(1, 8) : bad.file;
    EXPECT_NE(result.err.find(named), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.says), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad")) << result.err;
  }
}

// At the seam: the GDAL module itself opens no VRT, whoever calls it.
TEST_F(DemRuns, TheModuleRefusesAVrtWhateverItsPath) {
  write_hostile_vrt(dir_ / "passwd.vrt");
  const LocalFrame frame({48.6881, 10.8447, 450.0});
  try {
    (void)read_dem_terrain(dir_ / "passwd.vrt", frame, std::nullopt);
    FAIL() << "a VRT was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a VRT file"), std::string::npos) << e.what();
  }
}

// Found by fuzzing (fuzz_scene_files): a GeoTIFF whose geographic keys carry EPSG:4342, the code
// of a geocentric CRS. PROJ 9.1 crashed on it while choosing the transformation to WGS-84; the
// module refuses it first, in one line.
TEST_F(DemRuns, ACrsUnderTheCodeOfAnotherKindIsRefused) {
  fs::copy_file(fs::path(OWSIM_SOURCE_DIR) / "tests/data/dem_geocentric_code.tif",
                dir_ / "geocentric_code.tif");
  const LocalFrame frame({48.6881, 10.8447, 450.0});
  try {
    (void)read_dem_terrain(dir_ / "geocentric_code.tif", frame, std::nullopt);
    FAIL() << "read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "declares a geographic CRS under EPSG:4342, the code of a geocentric CRS"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace owsim
