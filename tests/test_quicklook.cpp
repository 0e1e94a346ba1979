// Protects quicklook/ (INTERFACE.md "`owsim run` outputs"): PNG files that OpenImageIO reads back
// pixel for pixel, range images with fibers in α order and lines in β order (flipped on downward
// sweeps), class colours and the range ramp in the right cells, the map's terrain, conductors,
// poles, trees, trajectory and hits where their coordinates say, every Nth frame only, and no
// file left as .partial.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/images/png_image.hpp"
#include "io/images/quicklook.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

constexpr int kScale = 4;  // the default enlargement

class QuicklookTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("owsim_test_quicklook_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  [[nodiscard]] std::filesystem::path quicklook_dir() const { return directory_ / "out/quicklook"; }

  [[nodiscard]] std::set<std::string> files() const {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(quicklook_dir())) {
      names.insert(entry.path().filename().string());
    }
    return names;
  }

  std::filesystem::path directory_;
};

QuicklookOptions fast_options() {
  QuicklookOptions options;
  options.file_options.sync_on_commit = false;
  return options;
}

// A PNG read back through OpenImageIO's ImageInput.
struct DecodedImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::uint8_t> bytes;

  [[nodiscard]] Rgb8 at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {bytes[i], bytes[i + 1], bytes[i + 2]};
  }
};

DecodedImage read_png(const std::filesystem::path& path) {
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) throw std::runtime_error("cannot open " + path.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  DecodedImage image{spec.width, spec.height, spec.nchannels, {}};
  EXPECT_EQ(input->format_name(), std::string("png"));
  EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT8);
  image.bytes.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, image.bytes.data())) {
    throw std::runtime_error("cannot read " + path.string() + ": " + input->geterror());
  }
  return image;
}

// A frame whose pulses come from the scan pattern and whose returns the test sets by hand.
struct QuicklookFrame {
  FrameSweep sweep;
  std::vector<Pulse> pulses;
  std::vector<PulseRay> rays;
  std::vector<PulseReturns> returns;

  QuicklookFrame(const ScanParams& scan, std::int64_t frame) : sweep(frame_sweep(scan, 7, frame)) {
    for (int k = 0; k < scan.pulses_per_frame(); ++k) {
      pulses.push_back(pulse_of_frame(scan, sweep, k));
    }
    rays.resize(pulses.size());
    returns.resize(pulses.size());
  }

  [[nodiscard]] FrameView view() const { return {sweep.frame, sweep, pulses, rays, returns}; }

  // The pulse of (line, fiber), found by search rather than by the slot formula.
  [[nodiscard]] std::size_t index_of(int line, int fiber) const {
    for (std::size_t k = 0; k < pulses.size(); ++k) {
      if (pulses[k].line == line && pulses[k].fiber == fiber) return k;
    }
    throw std::runtime_error("no pulse for line " + std::to_string(line));
  }

  void add_return(int line, int fiber, double range_m, SurfaceClass surface) {
    PulseReturns& r = returns[index_of(line, fiber)];
    r.returns[r.count].range_m = range_m;
    r.returns[r.count].surface = static_cast<std::uint8_t>(surface);
    ++r.count;
  }
};

// Row of a fiber counted from the spec's α table: the fibers (reference excluded) with a higher α,
// plus those of equal α and a lower number.
int expected_row(const ScanParams& scan, int fiber) {
  const double alpha = fiber_alpha_deg(scan, fiber);
  int row = 0;
  for (int other = 1; other < scan.fibers_per_line; ++other) {
    const double a = fiber_alpha_deg(scan, other);
    if (a > alpha || (a == alpha && other < fiber)) ++row;
  }
  return row;
}

// The centre of a cell's enlarged block.
Rgb8 cell(const DecodedImage& image, int row, int column) {
  return image.at(column * kScale + kScale / 2, row * kScale + kScale / 2);
}

TEST(QuicklookNames, FrameFileName) {
  EXPECT_EQ(quicklook_frame_file_name(0), "frame_000000.png");
  EXPECT_EQ(quicklook_frame_file_name(10), "frame_000010.png");
  EXPECT_EQ(quicklook_frame_file_name(1'234'567), "frame_1234567.png");
}

TEST(QuicklookRows, SpecAlphaOrder) {
  const ScanParams scan;
  // α: fibers 65..126 run +21° → +21/62°, fibers 64 and 127 both at 0°, fibers 63..1 down to −21°.
  EXPECT_EQ(expected_row(scan, 65), 0);
  EXPECT_EQ(expected_row(scan, 64), 62);
  EXPECT_EQ(expected_row(scan, 127), 63);
  EXPECT_EQ(expected_row(scan, 30), 97);
  EXPECT_EQ(expected_row(scan, 1), 126);
}

TEST(PngImage, RampEndsAndMiddle) {
  EXPECT_EQ(range_ramp_colour(0.0), (Rgb8{247, 251, 255}));
  EXPECT_EQ(range_ramp_colour(0.5), (Rgb8{107, 174, 214}));
  EXPECT_EQ(range_ramp_colour(1.0), (Rgb8{8, 48, 107}));
  EXPECT_EQ(range_ramp_colour(-3.0), range_ramp_colour(0.0));
  EXPECT_EQ(range_ramp_colour(7.0), range_ramp_colour(1.0));
  EXPECT_EQ(range_ramp_colour(std::numeric_limits<double>::quiet_NaN()), range_ramp_colour(1.0));
  // Halfway between the first two control points.
  EXPECT_EQ(range_ramp_colour(1.0 / 16.0), (Rgb8{235, 243, 251}));
  // Monotonic darkening.
  int previous = 3 * 256;
  for (int i = 0; i <= 100; ++i) {
    const Rgb8 c = range_ramp_colour(i / 100.0);
    const int sum = c.r + c.g + c.b;
    EXPECT_LE(sum, previous) << "t = " << i / 100.0;
    previous = sum;
  }
}

TEST(PngImage, DrawingClipsAndEnlarges) {
  RgbImage image(20, 10, {1, 2, 3});
  const Rgb8 red{255, 0, 0};
  // A horizontal line far longer than the image, at row 4.
  draw_line(image, {-1e9, 4.0}, {1e9, 4.0}, red);
  for (int x = 0; x < 20; ++x) EXPECT_EQ(image.at(x, 4), red) << x;
  EXPECT_EQ(image.at(5, 3), (Rgb8{1, 2, 3}));
  // A diagonal: one pixel per step along the longer axis.
  RgbImage diagonal(10, 10);
  draw_line(diagonal, {0.0, 0.0}, {9.0, 9.0}, red);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(diagonal.at(i, i), red);
  EXPECT_EQ(diagonal.at(1, 0), Rgb8{});
  // A line wholly outside touches nothing.
  RgbImage outside(10, 10);
  draw_line(outside, {-5.0, -5.0}, {20.0, -3.0}, red);
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) EXPECT_EQ(outside.at(x, y), Rgb8{});
  }
  // A circle of radius 2: 13 pixels, clipped at the corner.
  RgbImage disc(10, 10);
  fill_circle(disc, 5, 5, 2, red);
  int count = 0;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) count += disc.at(x, y) == red ? 1 : 0;
  }
  EXPECT_EQ(count, 13);
  RgbImage corner(10, 10);
  fill_circle(corner, 0, 0, 2, red);
  count = 0;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) count += corner.at(x, y) == red ? 1 : 0;
  }
  EXPECT_EQ(count, 6);  // (0,0) (1,0) (2,0) (0,1) (1,1) (0,2)

  RgbImage small(2, 1);
  small.set(1, 0, red);
  const RgbImage big = enlarged(small, 3);
  ASSERT_EQ(big.width(), 6);
  ASSERT_EQ(big.height(), 3);
  EXPECT_EQ(big.at(2, 2), Rgb8{});
  EXPECT_EQ(big.at(3, 0), red);
  EXPECT_EQ(big.at(5, 2), red);
  EXPECT_THROW((void)enlarged(small, 0), Error);
  EXPECT_THROW(RgbImage(0, 5), Error);
}

TEST_F(QuicklookTest, PngRoundTripsThroughOpenImageIo) {
  std::filesystem::create_directories(quicklook_dir());
  RgbImage image(7, 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      image.set(x, y, {static_cast<std::uint8_t>(x * 30), static_cast<std::uint8_t>(y * 50), 77});
    }
  }
  const auto path = quicklook_dir() / "t.png";
  write_png(path, image, {.sync_on_commit = false});
  const DecodedImage back = read_png(path);
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  ASSERT_EQ(back.channels, 3);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) EXPECT_EQ(back.at(x, y), image.at(x, y)) << x << "," << y;
  }
  EXPECT_EQ(files(), (std::set<std::string>{"t.png"}));
}

TEST_F(QuicklookTest, RangeImageCellsOnAnUpwardSweep) {
  const ScanParams scan;
  Quicklook quicklook(quicklook_dir(), Scene{}, scan,
                      {Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10)}, fast_options());
  QuicklookFrame frame(scan, 0);
  ASSERT_EQ(frame.sweep.direction, 1);
  for (int line = 50; line <= 60; ++line) frame.add_return(line, 30, 200.0, SurfaceClass::wire);
  frame.add_return(10, 40, 150.0, SurfaceClass::ground);  // ground first, a tree behind it
  frame.add_return(10, 40, 160.0, SurfaceClass::tree);
  frame.add_return(10, 45, 90.0, SurfaceClass::pole);  // a pole first, a wire behind it
  frame.add_return(10, 45, 95.0, SurfaceClass::wire);
  frame.add_return(11, 45, 90.0, SurfaceClass::pole);
  frame.add_return(70, 100, 600.0, SurfaceClass::ground);
  frame.add_return(12, 50, 300.0, SurfaceClass::noise);  // a false return alone
  frame.add_return(13, 50, 80.0, SurfaceClass::noise);   // a false return before a wire
  frame.add_return(13, 50, 320.0, SurfaceClass::wire);
  frame.add_return(14, 50, 200.0, SurfaceClass::ground);  // ground before a false return
  frame.add_return(14, 50, 400.0, SurfaceClass::noise);
  quicklook.add_frame(frame.view());

  const DecodedImage image = read_png(quicklook_dir() / "frame_000000.png");
  ASSERT_EQ(image.channels, 3);
  ASSERT_EQ(image.width, 159 * kScale);
  ASSERT_EQ(image.height, 127 * kScale);
  const int row30 = expected_row(scan, 30);
  for (int line = 50; line <= 60; ++line) {
    EXPECT_EQ(cell(image, row30, line), kQuicklookWire) << line;
  }
  // Every pixel of the enlarged block carries the cell's colour.
  for (int dy = 0; dy < kScale; ++dy) {
    for (int dx = 0; dx < kScale; ++dx) {
      EXPECT_EQ(image.at(55 * kScale + dx, row30 * kScale + dy), kQuicklookWire);
    }
  }
  EXPECT_EQ(cell(image, row30, 49), kQuicklookNoReturn);
  EXPECT_EQ(cell(image, row30, 61), kQuicklookNoReturn);
  EXPECT_EQ(cell(image, row30 - 1, 55), kQuicklookNoReturn);
  EXPECT_EQ(cell(image, 0, 0), kQuicklookNoReturn);
  EXPECT_EQ(cell(image, expected_row(scan, 40), 10), kQuicklookTree);
  EXPECT_EQ(cell(image, expected_row(scan, 45), 10), kQuicklookWire);
  EXPECT_EQ(cell(image, expected_row(scan, 45), 11), kQuicklookPole);
  const Rgb8 ground = cell(image, expected_row(scan, 100), 70);
  EXPECT_EQ(ground, range_ramp_colour(600.0 / timeout_range_m(scan.counter)));
  EXPECT_NE(ground, kQuicklookNoReturn);
  const int row50 = expected_row(scan, 50);
  EXPECT_EQ(cell(image, row50, 12), (Rgb8{255, 230, 0}));  // yellow: a false return
  EXPECT_EQ(cell(image, row50, 13), kQuicklookWire);
  EXPECT_EQ(cell(image, row50, 14), range_ramp_colour(200.0 / timeout_range_m(scan.counter)));
  EXPECT_EQ(files(), (std::set<std::string>{"frame_000000.png"}));
}

TEST_F(QuicklookTest, DownwardSweepIsFlippedSoBetaRisesToTheRight) {
  const ScanParams scan;
  QuicklookOptions options = fast_options();
  options.every_nth_frame = 1;
  options.range_full_scale_m = 400.0;
  Quicklook quicklook(quicklook_dir(), Scene{}, scan,
                      {Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10)}, options);
  QuicklookFrame frame(scan, 1);
  ASSERT_EQ(frame.sweep.direction, -1);
  // β falls with the line on this frame: line 0 has the highest β, so it is the last column.
  ASSERT_GT(frame.pulses[frame.index_of(0, 30)].beta_deg,
            frame.pulses[frame.index_of(158, 30)].beta_deg);
  for (int line = 50; line <= 52; ++line) frame.add_return(line, 30, 200.0, SurfaceClass::wire);
  frame.add_return(0, 64, 100.0, SurfaceClass::ground);
  quicklook.add_frame(frame.view());

  const DecodedImage image = read_png(quicklook_dir() / "frame_000001.png");
  const int row30 = expected_row(scan, 30);
  for (int line = 50; line <= 52; ++line) {
    EXPECT_EQ(cell(image, row30, 158 - line), kQuicklookWire) << line;
    EXPECT_EQ(cell(image, row30, line), kQuicklookNoReturn) << line;
  }
  EXPECT_EQ(cell(image, 62, 158), range_ramp_colour(0.25));  // fiber 64 is row 62
  EXPECT_EQ(cell(image, 62, 0), kQuicklookNoReturn);
}

TEST_F(QuicklookTest, EveryNthFrameAndNothingPartial) {
  const ScanParams scan;
  Quicklook quicklook(quicklook_dir(), Scene{}, scan,
                      {Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10)}, fast_options());
  EXPECT_TRUE(std::filesystem::is_directory(quicklook_dir()));
  for (const std::int64_t f : {0, 5, 10, 13}) {
    const QuicklookFrame frame(scan, f);
    quicklook.add_frame(frame.view());
  }
  EXPECT_EQ(files(), (std::set<std::string>{"frame_000000.png", "frame_000010.png"}));
  quicklook.finish();
  EXPECT_EQ(files(), (std::set<std::string>{"frame_000000.png", "frame_000010.png", "map.png"}));
  EXPECT_THROW(quicklook.finish(), Error);
  EXPECT_THROW(quicklook.add_trajectory_point(Eigen::Vector3d::Zero()), Error);
  EXPECT_THROW(quicklook.add_frame(QuicklookFrame(scan, 20).view()), Error);
  EXPECT_FALSE(std::filesystem::exists(quicklook_dir() / "frame_000020.png"));
}

TEST_F(QuicklookTest, NoRangeImagesWhenNIsZero) {
  const ScanParams scan;
  QuicklookOptions options = fast_options();
  options.every_nth_frame = 0;
  Quicklook quicklook(quicklook_dir(), Scene{}, scan,
                      {Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10)}, options);
  quicklook.add_frame(QuicklookFrame(scan, 0).view());
  quicklook.finish();
  EXPECT_EQ(files(), (std::set<std::string>{"map.png"}));
}

// The map: 600 × 600 m at 1 m a pixel, so (e, n) = (i − 299.5, 299.5 − j) is the centre of
// pixel (column i, row j).
TEST_F(QuicklookTest, MapDrawsObjectsTrajectoryAndHits) {
  const ScanParams scan;
  Scene scene;
  scene.terrain.kind = TerrainKind::flat;
  scene.conductors.push_back({"span/1", {{-200.5, 100.5, 20.0}, {199.5, 100.5, 20.0}}, 0.01, 0.4});
  scene.cylinders.push_back({"pole1", SurfaceClass::pole, {50.5, -50.5, 0.0}, 0.3, 20.0, 0.3});
  scene.cylinders.push_back({"tree1", SurfaceClass::tree, {-100.5, -100.5, 0.0}, 3.0, 12.0, 0.3});
  QuicklookOptions options = fast_options();
  options.map_size_px = 600;
  Quicklook quicklook(quicklook_dir(), scene, scan,
                      {Eigen::Vector2d(-300, -300), Eigen::Vector2d(300, 300)}, options);
  ASSERT_EQ(quicklook.map_width_px(), 600);
  ASSERT_EQ(quicklook.map_height_px(), 600);
  quicklook.add_trajectory_point({-250.5, -200.5, 100.0});
  quicklook.add_trajectory_point({249.5, -200.5, 100.0});

  QuicklookFrame frame(scan, 3);  // not an Nth frame: hits only
  for (PulseRay& ray : frame.rays) {
    ray.origin_enu_m = {120.5, -200.5, 100.0};
    ray.dir_enu = {0.0, 1.0, 0.0};
  }
  frame.add_return(20, 30, 100.0, SurfaceClass::ground);  // (120.5, −100.5)
  frame.add_return(20, 30, 250.0, SurfaceClass::wire);    // (120.5, 49.5)
  frame.add_return(21, 30, 150.0, SurfaceClass::pole);    // (120.5, −50.5)
  frame.add_return(22, 30, 50.0, SurfaceClass::tree);     // (120.5, −150.5)
  frame.add_return(23, 30, 5000.0, SurfaceClass::wire);   // off the map: dropped
  frame.add_return(24, 30, 200.0, SurfaceClass::noise);  // (120.5, −0.5): a false return, no place
  frame.add_return(25, 30, 220.0, SurfaceClass::fog);    // (120.5, 19.5): a fog echo, no place
  quicklook.add_frame(frame.view());
  quicklook.finish();

  const DecodedImage map = read_png(quicklook_dir() / "map.png");
  ASSERT_EQ(map.width, 600);
  ASSERT_EQ(map.height, 600);
  ASSERT_EQ(map.channels, 3);
  EXPECT_EQ(map.at(10, 10), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(300, 199), kQuicklookConductor);  // (0.5, 100.5)
  EXPECT_EQ(map.at(100, 199), kQuicklookConductor);  // (−199.5, 100.5)
  EXPECT_EQ(map.at(300, 198), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(550, 199), kQuicklookFlatTerrain);  // beyond the conductor's end
  EXPECT_EQ(map.at(350, 350), kQuicklookPoleObject);   // (50.5, −50.5), a 2 px disc
  EXPECT_EQ(map.at(352, 350), kQuicklookPoleObject);
  EXPECT_EQ(map.at(353, 350), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(199, 400), kQuicklookTreeObject);  // (−100.5, −100.5), radius 3 m
  EXPECT_EQ(map.at(202, 400), kQuicklookTreeObject);
  EXPECT_EQ(map.at(203, 400), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(300, 500), kQuicklookTrajectory);  // (0.5, −200.5), 3 px wide
  EXPECT_EQ(map.at(300, 501), kQuicklookTrajectory);
  EXPECT_EQ(map.at(300, 502), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(49, 500), kQuicklookTrajectory);  // the first point, (−250.5, −200.5)
  EXPECT_EQ(map.at(48, 500), kQuicklookTrajectory);  // widened by a pixel
  EXPECT_EQ(map.at(47, 500), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(420, 400), kQuicklookGroundHit);
  EXPECT_EQ(map.at(421, 400), kQuicklookFlatTerrain);  // ground hits are single pixels
  EXPECT_EQ(map.at(420, 250), kQuicklookWire);
  EXPECT_EQ(map.at(421, 250), kQuicklookWire);  // obstacle hits are 3 px dots
  EXPECT_EQ(map.at(420, 350), kQuicklookPole);
  EXPECT_EQ(map.at(420, 450), kQuicklookTree);
  EXPECT_EQ(map.at(420, 300), kQuicklookFlatTerrain);
  EXPECT_EQ(map.at(420, 280), kQuicklookFlatTerrain);
  EXPECT_EQ(files(), (std::set<std::string>{"map.png"}));
}

TEST_F(QuicklookTest, GridTerrainIsShadedByHeight) {
  const ScanParams scan;
  Scene scene;
  scene.terrain.kind = TerrainKind::grid;
  HeightGrid& grid = scene.terrain.grid;
  grid.ncols = 3;
  grid.nrows = 3;
  grid.x_west_m = -50.0;
  grid.y_south_m = -50.0;
  grid.cellsize_m = 50.0;
  grid.heights = {100, 100, 100,  // north row: highest
                  50,  50,  50,   //
                  0,   0,   -9999};
  grid.nodata = -9999.0;
  QuicklookOptions options = fast_options();
  options.map_size_px = 200;
  Quicklook quicklook(quicklook_dir(), scene, scan,
                      {Eigen::Vector2d(-100, -100), Eigen::Vector2d(100, 100)}, options);
  quicklook.finish();
  const DecodedImage map = read_png(quicklook_dir() / "map.png");
  const auto brightness = [&](int x, int y) {
    const Rgb8 c = map.at(x, y);
    return c.r + c.g + c.b;
  };
  EXPECT_EQ(map.at(5, 5), kQuicklookNoTerrain);           // (−94.5, 94.5): off the grid
  EXPECT_EQ(map.at(150, 150), kQuicklookNoTerrain);       // nearest sample is NODATA
  EXPECT_GT(brightness(100, 50), brightness(100, 100));   // north sample above the middle
  EXPECT_GT(brightness(100, 100), brightness(100, 150));  // middle above the south
  EXPECT_NE(map.at(100, 150), kQuicklookNoTerrain);
}

TEST(QuicklookRegion, SceneAndPointsWithMargin) {
  Scene scene;
  scene.conductors.push_back({"s/1", {{-10.0, 5.0, 20.0}, {30.0, 6.0, 21.0}}, 0.01, 0.4});
  scene.cylinders.push_back({"p", SurfaceClass::pole, {0.0, -20.0, 0.0}, 0.5, 20.0, 0.3});
  const std::vector<Eigen::Vector3d> trajectory = {{-40.0, 0.0, 100.0}, {0.0, 60.0, 100.0}};
  const Eigen::AlignedBox2d box = quicklook_map_region(scene, trajectory, 10.0);
  EXPECT_EQ(box.min(), Eigen::Vector2d(-50.0, -30.5));
  EXPECT_EQ(box.max(), Eigen::Vector2d(40.0, 70.0));
  const Eigen::AlignedBox2d empty = quicklook_map_region(Scene{}, {}, 25.0);
  EXPECT_EQ(empty.min(), Eigen::Vector2d(-25.0, -25.0));
  EXPECT_EQ(empty.max(), Eigen::Vector2d(25.0, 25.0));
  EXPECT_THROW((void)quicklook_map_region(scene, trajectory, -1.0), Error);
}

TEST_F(QuicklookTest, RejectsBadSetUpAndMismatchedFrames) {
  const ScanParams scan;
  const Eigen::AlignedBox2d region(Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10));
  EXPECT_THROW(Quicklook(quicklook_dir(), Scene{}, scan, Eigen::AlignedBox2d{}, fast_options()),
               Error);
  EXPECT_THROW(Quicklook(quicklook_dir(), Scene{}, scan,
                         {Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 0)}, fast_options()),
               Error);
  QuicklookOptions bad = fast_options();
  bad.every_nth_frame = -1;
  EXPECT_THROW(Quicklook(quicklook_dir(), Scene{}, scan, region, bad), Error);
  bad = fast_options();
  bad.map_size_px = 8;
  EXPECT_THROW(Quicklook(quicklook_dir(), Scene{}, scan, region, bad), Error);
  bad = fast_options();
  bad.range_full_scale_m = -1.0;
  EXPECT_THROW(Quicklook(quicklook_dir(), Scene{}, scan, region, bad), Error);

  // A file where the directory should be.
  std::filesystem::create_directories(directory_);
  { std::ofstream(directory_ / "blocker") << "x"; }
  EXPECT_THROW(Quicklook(directory_ / "blocker" / "q", Scene{}, scan, region, fast_options()),
               Error);

  Quicklook quicklook(quicklook_dir(), Scene{}, scan, region, fast_options());
  QuicklookFrame frame(scan, 0);
  frame.rays.pop_back();
  EXPECT_THROW(quicklook.add_frame(frame.view()), Error);
  QuicklookFrame wrong(scan, 0);
  wrong.pulses[5].line = 159;
  EXPECT_THROW(quicklook.add_frame(wrong.view()), Error);
  EXPECT_EQ(files(), (std::set<std::string>{}));
}

}  // namespace
}  // namespace owsim
