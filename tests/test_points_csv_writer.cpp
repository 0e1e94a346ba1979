// Protects points.csv (INTERFACE.md "`owsim run` outputs"): the exact header, every column
// round-tripping to its stated decimals, the spellings of unknown values, object ids from the
// table, and that no file appears under the final name before finish() or after a failure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/points/points_csv_writer.hpp"

namespace owsim {
namespace {

class PointsCsvWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("owsim_test_points_csv_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  [[nodiscard]] std::filesystem::path path() const { return directory_ / "points.csv"; }

  std::filesystem::path directory_;
};

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Splits a CSV line on commas (the cells under test hold no quotes unless stated).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

int decimals_of(const std::string& cell) {
  const auto dot = cell.find('.');
  return dot == std::string::npos ? 0 : static_cast<int>(cell.size() - dot - 1);
}

PointRecord sample_point() {
  PointRecord p;
  p.frame = 123456789012;
  p.pulse = 20351;
  p.line = 159;
  p.fiber = 127;
  p.return_number = 2;
  p.number_of_returns = 2;
  p.time_s = 1234.123456789321;
  p.range_m = 987.654321987;
  p.counter = 4095;
  p.enu_m = {-1234.567891234, 98765.43219876, -12.3456789};
  p.geodetic = {48.688112345678912, -10.844712345678912, 562.123456789};
  p.surface = SurfaceClass::wire;
  p.object_index = 1;
  p.energy_rel = 0.0123456789123;
  p.incidence_deg = 37.123456789;
  p.scan_angle_deg = -12.5;
  return p;
}

TEST_F(PointsCsvWriterTest, HeaderIsExactlyTheInterfaceColumns) {
  PointsCsvWriter writer(path(), {});
  writer.finish();
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0],
            "frame,pulse,line,fiber,return,time_s,range_m,counter,e_m,n_m,u_m,lat_deg,lon_deg,h_m,"
            "class,object,energy_rel,incidence_deg");
}

TEST_F(PointsCsvWriterTest, RowRoundTripsEveryValueToItsStatedDecimals) {
  const PointRecord p = sample_point();
  PointsCsvWriter writer(path(), {"span_a/1", "span_a/2"});
  writer.write(std::span(&p, 1));
  writer.finish();
  EXPECT_EQ(writer.points_written(), 1u);
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), 2u);
  const auto c = cells(lines[1]);
  ASSERT_EQ(c.size(), 18u) << lines[1];
  EXPECT_EQ(c[0], "123456789012");
  EXPECT_EQ(c[1], "20351");
  EXPECT_EQ(c[2], "159");
  EXPECT_EQ(c[3], "127");
  EXPECT_EQ(c[4], "2");
  EXPECT_EQ(c[7], "4095");
  EXPECT_EQ(c[14], "wire");
  EXPECT_EQ(c[15], "span_a/2");
  // Fixed decimals per column, and the value within half a unit of the last decimal.
  struct Column {
    int index;
    double value;
    int decimals;
  };
  const Column fixed[] = {{5, p.time_s, 9},
                          {6, p.range_m, 4},
                          {8, p.enu_m.x(), 4},
                          {9, p.enu_m.y(), 4},
                          {10, p.enu_m.z(), 4},
                          {11, p.geodetic.lat_deg, 9},
                          {12, p.geodetic.lon_deg, 9},
                          {13, p.geodetic.h_m, 4},
                          {17, p.incidence_deg, 4}};
  for (const Column& column : fixed) {
    const std::string& cell = c[static_cast<std::size_t>(column.index)];
    EXPECT_EQ(decimals_of(cell), column.decimals) << "column " << column.index << ": " << cell;
    const double unit = std::pow(10.0, -column.decimals);
    EXPECT_NEAR(std::stod(cell), column.value, 0.5 * unit * (1 + 1e-6))
        << "column " << column.index << ": " << cell;
  }
  EXPECT_EQ(c[5], "1234.123456789");
  EXPECT_EQ(c[8], "-1234.5679");
  EXPECT_EQ(c[12], "-10.844712346");
  // energy_rel: 9 significant digits.
  EXPECT_EQ(c[16], "0.0123456789");
  EXPECT_NEAR(std::stod(c[16]), p.energy_rel, 0.5e-10);
}

TEST_F(PointsCsvWriterTest, UnknownClassObjectEnergyAndIncidence) {
  PointRecord p = sample_point();
  p.surface = std::nullopt;
  p.object_index = kNoObject;
  p.energy_rel = std::numeric_limits<double>::quiet_NaN();
  p.incidence_deg = std::numeric_limits<double>::quiet_NaN();
  PointsCsvWriter writer(path(), {"a"});
  writer.write(std::span(&p, 1));
  writer.finish();
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), 2u);
  const auto c = cells(lines[1]);
  ASSERT_EQ(c.size(), 18u) << lines[1];
  EXPECT_EQ(c[14], "unknown");
  EXPECT_EQ(c[15], "");
  EXPECT_EQ(c[16], "");
  EXPECT_EQ(c[17], "");
}

TEST_F(PointsCsvWriterTest, AFalseReturnIsNoiseWithNoObjectItsThresholdAndNoIncidence) {
  PointRecord p = sample_point();
  p.surface = SurfaceClass::noise;
  p.object_index = kNoObject;
  p.energy_rel = 0.0029;  // T
  p.incidence_deg = std::numeric_limits<double>::quiet_NaN();
  PointsCsvWriter writer(path(), {"span_a/1", "span_a/2"});
  writer.write(std::span(&p, 1));
  writer.finish();
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1],
            "123456789012,20351,159,127,2,1234.123456789,987.6543,4095,-1234.5679,98765.4322,"
            "-12.3457,48.688112346,-10.844712346,562.1235,noise,,0.0029,");
}

TEST_F(PointsCsvWriterTest, EveryClassAndObjectIdFromTheTable) {
  const std::vector<std::string> ids = {"north/1", "pole 7", "oak, the big one", "say \"hi\"",
                                        "barn"};
  std::vector<PointRecord> points;
  const SurfaceClass classes[] = {SurfaceClass::wire, SurfaceClass::pole, SurfaceClass::tree,
                                  SurfaceClass::ground, SurfaceClass::building};
  for (std::uint32_t i = 0; i < 5; ++i) {
    PointRecord p = sample_point();
    p.surface = classes[i];
    p.object_index = i;
    points.push_back(p);
  }
  PointsCsvWriter writer(path(), ids);
  writer.write(points);
  writer.finish();
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), 6u);
  const std::string expected_class[] = {"wire", "pole", "tree", "ground", "building"};
  const std::string expected_object[] = {",north/1,", ",pole 7,", ",\"oak, the big one\",",
                                         ",\"say \"\"hi\"\"\",", ",barn,"};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NE(lines[i + 1].find("," + expected_class[i] + expected_object[i]), std::string::npos)
        << lines[i + 1];
  }
}

TEST_F(PointsCsvWriterTest, ZeroIsWrittenUnsigned) {
  PointRecord p = sample_point();
  p.enu_m = {-0.00004, 0.0, -0.0};
  p.incidence_deg = -0.00001;
  p.energy_rel = -0.0;
  PointsCsvWriter writer(path(), {"a", "b"});
  writer.write(std::span(&p, 1));
  writer.finish();
  const auto c = cells(read_lines(path()).at(1));
  EXPECT_EQ(c[8], "0.0000");
  EXPECT_EQ(c[9], "0.0000");
  EXPECT_EQ(c[10], "0.0000");
  EXPECT_EQ(c[16], "0");
  EXPECT_EQ(c[17], "0.0000");
}

TEST_F(PointsCsvWriterTest, ObjectIndexOutsideTheTableThrows) {
  PointRecord p = sample_point();
  p.object_index = 2;
  PointsCsvWriter writer(path(), {"a", "b"});
  EXPECT_THROW(writer.write(std::span(&p, 1)), Error);
}

TEST_F(PointsCsvWriterTest, ManyFramesStreamThroughTheBuffer) {
  // More than the 1 MiB buffer: every row arrives, in order.
  std::vector<PointRecord> frame(1000, sample_point());
  PointsCsvWriter writer(path(), {"a", "b"});
  for (int f = 0; f < 20; ++f) {
    for (std::size_t k = 0; k < frame.size(); ++k) {
      frame[k].frame = f;
      frame[k].pulse = static_cast<int>(k);
    }
    writer.write(frame);
  }
  writer.finish();
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), 20001u);
  EXPECT_GT(std::filesystem::file_size(path()), std::size_t{1} << 21);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto c = cells(lines[i]);
    ASSERT_EQ(std::stoll(c[0]), static_cast<long long>((i - 1) / 1000)) << i;
    ASSERT_EQ(std::stoi(c[1]), static_cast<int>((i - 1) % 1000)) << i;
  }
}

TEST_F(PointsCsvWriterTest, NothingUnderTheFinalNameBeforeFinish) {
  const PointRecord p = sample_point();
  PointsCsvWriter writer(path(), {"a", "b"});
  writer.write(std::span(&p, 1));
  EXPECT_FALSE(std::filesystem::exists(path()));
  writer.finish();
  EXPECT_TRUE(std::filesystem::exists(path()));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(path())));
}

TEST_F(PointsCsvWriterTest, AnExceptionBeforeFinishLeavesNoFile) {
  try {
    const PointRecord p = sample_point();
    PointsCsvWriter writer(path(), {"a", "b"});
    writer.write(std::span(&p, 1));
    throw std::runtime_error("simulation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(path()));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(path())));
}

}  // namespace
}  // namespace owsim
