// Protects trajectory.csv (INTERFACE.md "`owsim run` outputs"): the exact header, positions on
// WGS-84 through the scenario's local frame, the stated decimals, that owsim's own CSV reader
// reads the file back, and that no file appears under the final name before finish().
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/trajectory/trajectory_csv_reader.hpp"
#include "io/trajectory/trajectory_csv_writer.hpp"

namespace owsim {
namespace {

class TrajectoryCsvWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("owsim_test_trajectory_csv_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  [[nodiscard]] std::filesystem::path path() const { return directory_ / "trajectory.csv"; }

  std::filesystem::path directory_;
  LocalFrame frame_{Geodetic{48.6881, 10.8447, 450.0}};
};

std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

std::vector<Pose> sample_poses() {
  std::vector<Pose> poses;
  for (int k = 0; k < 5; ++k) {
    Pose pose;
    pose.time_s = 100.0 + k / 3.0;
    pose.position_enu_m = {-1200.123456 + 13.5 * k, 2500.987654 - 7.25 * k, 100.0 + 0.125 * k};
    pose.attitude = {1.123456789123 * k, -4.5 + 0.01 * k, 359.9 - 90.0 * k};
    poses.push_back(pose);
  }
  return poses;
}

TEST_F(TrajectoryCsvWriterTest, HeaderAndOneRowPerPose) {
  TrajectoryCsvWriter writer(path(), frame_);
  const auto poses = sample_poses();
  writer.write(poses);
  writer.finish();
  EXPECT_EQ(writer.rows_written(), poses.size());
  const auto lines = read_lines(path());
  ASSERT_EQ(lines.size(), poses.size() + 1);
  EXPECT_EQ(lines[0], "time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg");
}

TEST_F(TrajectoryCsvWriterTest, ColumnsHoldTheLocalFrameValuesToTheirDecimals) {
  const auto poses = sample_poses();
  TrajectoryCsvWriter writer(path(), frame_);
  writer.write(poses);
  writer.finish();
  const auto lines = read_lines(path());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const auto c = cells(lines[k + 1]);
    ASSERT_EQ(c.size(), 10u) << lines[k + 1];
    const Pose& pose = poses[k];
    const Geodetic g = frame_.geodetic_from_enu(pose.position_enu_m);
    const double expected[] = {pose.time_s,
                               g.lat_deg,
                               g.lon_deg,
                               g.h_m,
                               pose.position_enu_m.x(),
                               pose.position_enu_m.y(),
                               pose.position_enu_m.z(),
                               pose.attitude.roll_deg,
                               pose.attitude.pitch_deg,
                               pose.attitude.heading_deg};
    const int decimals[] = {9, 9, 9, 4, 4, 4, 4, 9, 9, 9};
    for (std::size_t i = 0; i < 10; ++i) {
      const auto dot = c[i].find('.');
      ASSERT_NE(dot, std::string::npos) << c[i];
      EXPECT_EQ(static_cast<int>(c[i].size() - dot - 1), decimals[i]) << i << ": " << c[i];
      EXPECT_NEAR(std::stod(c[i]), expected[i], 0.5000001 * std::pow(10.0, -decimals[i]))
          << i << ": " << c[i];
    }
    // The written position maps back onto e/n/u through the frame within 0.2 mm.
    const Eigen::Vector3d back =
        frame_.enu_from_geodetic({std::stod(c[1]), std::stod(c[2]), std::stod(c[3])});
    EXPECT_LT((back - pose.position_enu_m).norm(), 2e-4);
  }
}

TEST_F(TrajectoryCsvWriterTest, OwsimsCsvReaderReadsItBack) {
  const auto poses = sample_poses();
  TrajectoryCsvWriter writer(path(), frame_);
  for (const Pose& pose : poses) writer.write(pose);
  writer.finish();
  const std::vector<NavRecord> records = read_trajectory_csv(path().string());
  ASSERT_EQ(records.size(), poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_NEAR(records[k].time_s, poses[k].time_s, 1e-9);
    const Eigen::Vector3d enu = frame_.enu_from_geodetic(records[k].position);
    EXPECT_LT((enu - poses[k].position_enu_m).norm(), 2e-4);
    EXPECT_NEAR(records[k].attitude.roll_deg, poses[k].attitude.roll_deg, 1e-9);
    EXPECT_NEAR(records[k].attitude.pitch_deg, poses[k].attitude.pitch_deg, 1e-9);
    EXPECT_NEAR(records[k].attitude.heading_deg, poses[k].attitude.heading_deg, 1e-9);
  }
}

TEST_F(TrajectoryCsvWriterTest, NothingUnderTheFinalNameBeforeFinishOrAfterAFailure) {
  {
    TrajectoryCsvWriter writer(path(), frame_);
    writer.write(sample_poses());
    EXPECT_FALSE(std::filesystem::exists(path()));
    writer.finish();
    EXPECT_TRUE(std::filesystem::exists(path()));
  }
  const auto other = directory_ / "other.csv";
  try {
    TrajectoryCsvWriter writer(other, frame_);
    writer.write(sample_poses());
    throw std::runtime_error("simulation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(other));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(other)));
}

}  // namespace
}  // namespace owsim
