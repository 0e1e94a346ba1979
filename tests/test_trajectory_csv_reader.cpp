// Protects the CSV trajectory reader (INTERFACE.md trajectory.format csv): columns found by
// name in any order, extra columns ignored, owsim's own trajectory.csv reads back, and
// malformed cells name the file, line and column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/error.hpp"
#include "io/trajectory/trajectory_csv_reader.hpp"
#include "sensor/trajectory.hpp"
#include "sensor/waypoint_plan.hpp"

namespace owsim {
namespace {

class CsvFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    std::ofstream(path_, std::ios::binary) << text;
    return path_;
  }
  std::string error_text(const std::string& text) {
    try {
      (void)read_trajectory_csv(write(text));
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("owsim_test_trajectory_csv_" + std::to_string(::getpid()) + ".csv"))
                          .string();
};

TEST_F(CsvFile, ColumnsInAnyOrderOthersIgnored) {
  const std::vector<NavRecord> records = read_trajectory_csv(
      write("heading_deg, speed_mps ,Time_S,lat_deg,\"lon_deg\",pitch_deg,roll_deg,h_m\r\n"
            "359.5,40,12.25,48.6881,10.8447,-2.5,3.25,512.75\r\n"
            "\r\n"
            "0.5,41,12.5,48.6882,10.8448,-2.0,3.0,513\r\n"));
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].time_s, 12.25);
  EXPECT_EQ(records[0].position.lat_deg, 48.6881);
  EXPECT_EQ(records[0].position.lon_deg, 10.8447);
  EXPECT_EQ(records[0].position.h_m, 512.75);
  EXPECT_EQ(records[0].attitude.roll_deg, 3.25);
  EXPECT_EQ(records[0].attitude.pitch_deg, -2.5);
  EXPECT_EQ(records[0].attitude.heading_deg, 359.5);
  EXPECT_EQ(records[1].time_s, 12.5);
  EXPECT_EQ(records[1].attitude.heading_deg, 0.5);
}

TEST_F(CsvFile, OwsimTrajectoryCsvReadsBack) {
  // Write what `owsim run` writes (INTERFACE.md trajectory.csv) from a planned flight, read it
  // back, and get the same poses.
  const LocalFrame frame(Geodetic{48.6881, 10.8447, 450.0});
  WaypointPlan plan;
  plan.points_enu_m = {{-1200, 0, 100}, {400, 0, 100}, {400, 1500, 160}};
  TrajectoryOptions options;
  options.smoothing = {1, 0};
  const Trajectory original(waypoint_track(plan), frame, options);
  std::string text = "time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg\n";
  char row[512];
  for (double t = 0.0; t <= original.end_s(); t += 1.0 / 3.0) {
    const Pose pose = original.pose_at(t);
    const Geodetic g = frame.geodetic_from_enu(pose.position_enu_m);
    std::snprintf(row, sizeof row, "%.17g,%.12f,%.12f,%.6f,%.6f,%.6f,%.6f,%.9f,%.9f,%.9f\n", t,
                  g.lat_deg, g.lon_deg, g.h_m, pose.position_enu_m.x(), pose.position_enu_m.y(),
                  pose.position_enu_m.z(), pose.attitude.roll_deg, pose.attitude.pitch_deg,
                  pose.attitude.heading_deg);
    text += row;
  }
  const std::vector<NavRecord> records = read_trajectory_csv(write(text));
  const NavTrack track = to_local(records, frame);
  ASSERT_GT(track.time_s.size(), 100u);
  for (std::size_t i = 0; i < track.time_s.size(); ++i) {
    const Pose pose = original.pose_at(track.time_s[i]);
    EXPECT_NEAR((track.position_enu_m[i] - pose.position_enu_m).norm(), 0.0,
                1e-4);  // 12 decimals of a degree
    EXPECT_NEAR(track.attitude[i].roll_deg, pose.attitude.roll_deg, 1e-8);
    EXPECT_NEAR(track.attitude[i].heading_deg, pose.attitude.heading_deg, 1e-8);
  }
  const Trajectory reread(track, frame);
  EXPECT_NEAR((reread.pose_at(30.0).position_enu_m - original.pose_at(30.0).position_enu_m).norm(),
              0.0, 0.05);
}

// Regression (issue 45): a file saved by a spreadsheet starts with a UTF-8 byte-order mark, which
// hid the first column's name ("the header has no column 'time_s'"). Only a leading one is dropped.
TEST_F(CsvFile, AByteOrderMarkBeforeTheHeaderIsDropped) {
  const std::string header = "time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg,heading_deg\n";
  const std::string rows = "12.25,48.6881,10.8447,512.75,3.25,-2.5,359.5\n13,48.6,10.8,500,0,0,1\n";
  const std::vector<NavRecord> records = read_trajectory_csv(write("\xEF\xBB\xBF" + header + rows));
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].time_s, 12.25);
  EXPECT_EQ(records[0].attitude.heading_deg, 359.5);
  EXPECT_EQ(records[1].time_s, 13.0);
  // A mark anywhere else is no column name.
  EXPECT_NE(error_text(header + rows + "\xEF\xBB\xBF" + rows).find(path_ + ":4: time_s"),
            std::string::npos);
  EXPECT_NE(
      error_text("\n\xEF\xBB\xBF" + header + rows).find(path_ + ":2: the header has no column"),
      std::string::npos);
}

TEST_F(CsvFile, MalformedInputNamesFileLineAndColumn) {
  const std::string header = "time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg,heading_deg\n";
  EXPECT_EQ(error_text(header + "0,48.6,10.8,500,0,0,90\n1,48.6,10.8,500,abc,0,90\n"),
            path_ + ":3: roll_deg 'abc' is not a finite number");
  EXPECT_EQ(error_text(header + "0,48.6,10.8,NaN,0,0,90\n"),
            path_ + ":2: h_m 'NaN' is not a finite number");
  EXPECT_EQ(error_text(header + "0,48.6,10.8,500,0,0,\n"),
            path_ + ":2: heading_deg '' is not a finite number");
  EXPECT_EQ(error_text(header + "0,48.6,10.8,500,0\n"),
            path_ + ":2: expected at least 7 comma-separated cells, found 5");
  EXPECT_NE(error_text("time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg\n0,1,2,3,4,5\n")
                .find(path_ + ":1: the header has no column 'heading_deg'"),
            std::string::npos);
  EXPECT_NE(error_text("\ntime_s,time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg,heading_deg\n")
                .find(path_ + ":2: column 'time_s' appears twice"),
            std::string::npos);
  EXPECT_EQ(error_text(header), path_ + ": holds a header but no records");
  EXPECT_EQ(error_text(""), path_ + ": is empty: no header line");
  EXPECT_NE(error_text(header + "0,91,10.8,500,0,0,90\n").find(path_ + ":2: latitude 91"),
            std::string::npos);
  EXPECT_NE(error_text(header + "0,48.6,10.8,500,0,0,90\n").find("no error"), std::string::npos);
}

// Regression (issue 7): a time going back reached the spline as "trajectory record 2: …",
// naming neither the file nor the line.
TEST_F(CsvFile, TimeNotIncreasingNamesTheLine) {
  const std::string header = "time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg,heading_deg\n";
  const std::string row = ",48.6,10.8,500,0,0,90\n";
  EXPECT_EQ(error_text(header + "0" + row + "0.2" + row + "0.1" + row),
            path_ + ":4: time_s '0.1' is not after the previous record's");
  EXPECT_EQ(error_text(header + "0" + row + "\n0" + row),
            path_ + ":4: time_s '0' is not after the previous record's");
}

TEST(CsvReader, MissingFileIsAnError) {
  EXPECT_THROW((void)read_trajectory_csv("/nonexistent/owsim/trajectory.csv"), Error);
}

}  // namespace
}  // namespace owsim
