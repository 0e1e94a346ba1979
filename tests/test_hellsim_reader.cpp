// Protects the HellSim ASCII reader (SENSOR-SPEC §5, source table 7): the spec's example line
// parses to the right values, Time-Tag × tick weight with the first record at 0 and counter
// wraps, and malformed input names the file and line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/error.hpp"
#include "io/trajectory/hellsim_reader.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

const std::string kHeader =
    "Pic # Time-Tag Heading Pitch Roll X-Vel Y-Vel Z-Vel N-Vel E-Vel D-Vel Veloc Latitude Long. "
    "Altitude\n";
const std::string kExample =  // SENSOR-SPEC §5 / source table 7
    "3 5529 103.2374 0.45212 1.09571 46.08434 2.06451 -1.41685 -12.605 44.37 -1.76 46.16 "
    "48.68809 10.84468 1042.5143\n";

class HellSimFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    std::ofstream(path_) << text;
    return path_;
  }
  std::string error_text(const std::string& text, const HellSimOptions& options = {}) {
    try {
      (void)read_hellsim(write(text), options);
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("owsim_test_hellsim_" + std::to_string(::getpid()) + ".txt"))
                          .string();
};

TEST_F(HellSimFile, SpecExampleLine) {
  const std::vector<NavRecord> records =
      read_hellsim(write(kHeader + kExample +
                         "4 5531 103.5 0.5 1.2 46 2 -1.4 -12.6 44.4 -1.8 46.2 48.68810 10.84470 "
                         "1042.6\n"));
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].time_s, 0.0);
  EXPECT_EQ(records[0].attitude.heading_deg, 103.2374);
  EXPECT_EQ(records[0].attitude.pitch_deg, 0.45212);
  EXPECT_EQ(records[0].attitude.roll_deg, 1.09571);
  EXPECT_EQ(records[0].position.lat_deg, 48.68809);
  EXPECT_EQ(records[0].position.lon_deg, 10.84468);
  EXPECT_EQ(records[0].position.h_m, 1042.5143);
  EXPECT_DOUBLE_EQ(records[1].time_s, 2 * 0.0005);  // default tick 0.5 ms
  EXPECT_EQ(records[1].attitude.heading_deg, 103.5);
  EXPECT_EQ(records[1].position.h_m, 1042.6);
}

TEST_F(HellSimFile, TickWeightAndCounterWrap) {
  const std::string line_tail = " 90 0 0 0 0 0 0 0 0 0 48.7 10.8 500\n";
  const std::string text = kHeader + "1 65530" + line_tail + "2 65534" + line_tail + "3 2" +
                           line_tail + "4 40" + line_tail;
  HellSimOptions options;
  options.tick_s = 0.01;
  const std::vector<NavRecord> records = read_hellsim(write(text), options);
  ASSERT_EQ(records.size(), 4u);
  EXPECT_DOUBLE_EQ(records[1].time_s, 0.04);
  EXPECT_DOUBLE_EQ(records[2].time_s, 0.08);  // 65534 → 2 wraps: 4 counts
  EXPECT_DOUBLE_EQ(records[3].time_s, 0.46);
  // Without wrapping the same file goes back in time.
  options.tag_modulus = 0;
  EXPECT_NE(error_text(text, options).find(":4: Time-Tag 2 goes back"), std::string::npos)
      << error_text(text, options);
}

TEST_F(HellSimFile, ShortLineNamesFileAndLine) {
  const std::string text = kHeader + kExample +
                           "4 5531 103.5 0.5 1.2 46 2 -1.4 -12.6 44.4 -1.8 46.2 48.6881 10.8447 "
                           "1042.6\n" +
                           "5 5533 103.7 0.5 1.2 46 2 -1.4\n";
  EXPECT_EQ(error_text(text), path_ +
                                  ":4: expected 15 whitespace-separated columns (Pic # … "
                                  "Altitude), found 8");
}

TEST_F(HellSimFile, MalformedValuesNameFileAndLine) {
  EXPECT_EQ(error_text(kHeader + "3 5529 abc 0.45 1.09 46 2 -1.4 -12.6 44.37 -1.76 46.16 48.68 "
                                 "10.84 1042.5\n"),
            path_ + ":2: Heading 'abc' is not a finite number");
  EXPECT_EQ(error_text(kHeader + "3 5529 103 nan 1.09 46 2 -1.4 -12.6 44.37 -1.76 46.16 48.68 "
                                 "10.84 1042.5\n"),
            path_ + ":2: Pitch 'nan' is not a finite number");
  EXPECT_EQ(error_text(kHeader + kExample + kExample), path_ +
                                                           ":3: Time-Tag 5529 repeats the "
                                                           "previous record's");
  EXPECT_EQ(error_text(kHeader + "3 55.5 103 0 1 46 2 -1 -12 44 -1 46 48.68 10.84 1042\n"),
            path_ + ":2: Time-Tag '55.5' is not a whole count");
  EXPECT_NE(error_text(kHeader + "3 55 103 0 1 46 2 -1 -12 44 -1 46 98.68 10.84 1042\n")
                .find(":2: latitude 98.68"),
            std::string::npos);
  EXPECT_EQ(error_text(kHeader), path_ + ": holds no navigation records");
  EXPECT_NE(error_text("", {-1.0, 0}).find("tick"), std::string::npos);
}

TEST_F(HellSimFile, ReadsIntoATrajectory) {
  std::string text = kHeader;
  for (int i = 0; i < 40; ++i) {  // 60 Hz records (33 ticks of 0.5 ms ≈ 16.5 ms), heading 359 → 1
    const double heading = wrap_360_deg(359.0 + 0.05 * i);
    text += std::to_string(i) + " " + std::to_string(1000 + 33 * i) + " " +
            std::to_string(heading) + " 0.5 1.0 46 0 0 46 0 0 46 48.68809 " +
            std::to_string(10.84468 + 1e-5 * i) + " 1042.5\n";
  }
  const std::vector<NavRecord> records = read_hellsim(write(text));
  const LocalFrame frame(records.front().position);
  const Trajectory trajectory(to_local(records, frame), frame);
  EXPECT_NEAR(trajectory.end_s(), 39 * 33 * 0.0005, 1e-12);
  for (double t = 0.0; t < trajectory.end_s(); t += 0.01) {
    EXPECT_NEAR(trajectory.heading_rate_deg_per_s(t), 0.05 / (33 * 0.0005), 1e-3);
  }
}

}  // namespace
}  // namespace owsim
