// flight.mcap (output mcap, io/run/flight_mcap.hpp) through `owsim run`: the same bytes for any
// thread count and beside any other outputs, chunks cut at frames, not written unless asked for,
// a resume refused; the transforms' axes and the clock's shift of a flight that starts before 0.
// The reference readers' check of a flown file is tests/mcap/read_flight.mjs (ctest
// mcap_flight_reference_reader).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "io/run/flight_mcap.hpp"
#include "io/run/output_kind.hpp"

namespace owsim {
namespace {

using test::read_whole_file;
using test::run_cli;
using test::TempDir;

const std::string kCorridor = std::string(OWSIM_SOURCE_DIR) + "/examples/corridor.yaml";

test::CliResult fly(const TempDir& work, const std::string& out, const std::string& threads,
                    const std::string& outputs, std::vector<std::string> more = {}) {
  std::vector<std::string> arguments = {"run",       kCorridor, "--frames", "3",
                                        "--threads", threads,   "--out",    out,
                                        "--outputs", outputs,   "--quiet"};
  arguments.insert(arguments.end(), more.begin(), more.end());
  return run_cli(arguments, work.path());
}

std::uint64_t le(const std::string& bytes, std::size_t at, int width) {
  std::uint64_t value = 0;
  for (int i = 0; i < width; ++i) {
    value |= std::uint64_t{static_cast<unsigned char>(bytes.at(at + i))} << (8 * i);
  }
  return value;
}

// The opcodes of the data section's top-level records (magic to Data End).
std::vector<int> data_section_opcodes(const std::string& file) {
  std::vector<int> opcodes;
  std::size_t at = 8;
  while (at + 9 <= file.size()) {
    const int opcode = static_cast<unsigned char>(file[at]);
    opcodes.push_back(opcode);
    if (opcode == 0x0F) break;
    at += 9 + le(file, at + 1, 8);
  }
  return opcodes;
}

TEST(FlightMcap, SameBytesForAnyThreadCountAndBesideOtherOutputs) {
  const TempDir work("owsim_flight_mcap");
  ASSERT_EQ(fly(work, "one", "1", "mcap").exit_status, 0);
  ASSERT_EQ(fly(work, "two", "2", "mcap").exit_status, 0);
  const test::CliResult beside =
      fly(work, "beside", "2", "d64,points,trajectory,summary,truth,mcap");
  ASSERT_EQ(beside.exit_status, 0) << beside.err;
  const std::string one = read_whole_file(work / "one/flight.mcap");
  ASSERT_GT(one.size(), 100000u);
  EXPECT_EQ(read_whole_file(work / "two/flight.mcap"), one);
  EXPECT_EQ(read_whole_file(work / "beside/flight.mcap"), one);
  EXPECT_EQ(read_whole_file(work / "beside/metadata.yaml"),
            read_whole_file(work / "one/metadata.yaml"));
  // Only what was asked for: flight.mcap, metadata.yaml and the scenario as flown.
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(work / "one")) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"flight.mcap", "metadata.yaml", "scenario.yaml"}));

  // One chunk of schemas, channels and latched messages, then one chunk a frame, each followed by
  // its message indexes: the scene and /tf_static in the first, cloud, /tf and fix in each other.
  const std::vector<int> opcodes = data_section_opcodes(one);
  EXPECT_EQ(opcodes, (std::vector<int>{0x01, 0x06, 0x07, 0x07, 0x06, 0x07, 0x07, 0x07, 0x06, 0x07,
                                       0x07, 0x07, 0x06, 0x07, 0x07, 0x07, 0x0F}));
}

TEST(FlightMcap, NotWrittenUnlessAskedForByName) {
  EXPECT_FALSE(all_outputs().contains(OutputKind::mcap));
  EXPECT_TRUE(parse_output_list("mcap,csv").contains(OutputKind::mcap));
  EXPECT_EQ(output_list(parse_output_list("trajectory,mcap")), "trajectory,mcap");
  const TempDir work("owsim_flight_mcap");
  const test::CliResult all = run_cli(
      {"run", kCorridor, "--frames", "1", "--out", "all", "--quiet", "--outputs", "d64,summary"},
      work.path());
  ASSERT_EQ(all.exit_status, 0) << all.err;
  EXPECT_FALSE(std::filesystem::exists(work / "all/flight.mcap"));
  EXPECT_FALSE(std::filesystem::exists(work / "all/metadata.yaml"));
}

TEST(FlightMcap, AResumeIsRefusedInOneLineAndTouchesNothing) {
  const TempDir work("owsim_flight_mcap");
  const test::CliResult refused = fly(work, "out", "2", "mcap", {"--resume"});
  EXPECT_NE(refused.exit_status, 0);
  EXPECT_EQ(refused.err,
            "owsim: --resume: flight.mcap (output mcap) cannot be continued from a checkpoint; run "
            "without --resume, or without mcap\n");
  EXPECT_FALSE(std::filesystem::exists(work / "out"));
}

TEST(FlightMcap, AResumedSweepRunsAnUnfinishedMemberOverInsteadOfRefusingIt) {
  const TempDir work("owsim_flight_mcap");
  std::filesystem::copy_file(std::string(OWSIM_SOURCE_DIR) + "/examples/single_span.yaml",
                             work / "single_span.yaml");
  {
    std::ofstream sweep(work / "sweep.yaml");
    sweep << "base: single_span.yaml\ncount: 2\nseed: 7\noutputs: mcap\n"
             "vary:\n  seed: {member: true}\n";
  }
  const std::vector<std::string> arguments = {"sweep", "sweep.yaml", "--out", "out", "--quiet"};
  ASSERT_EQ(run_cli(arguments, work.path()).exit_status, 0);
  const std::string member = read_whole_file(work / "out/1/flight.mcap");
  ASSERT_GT(member.size(), 1000u);
  // Member 1 unfinished (no summary.json): --resume flies it again from frame 0.
  std::filesystem::remove(work / "out/1/summary.json");
  std::filesystem::remove(work / "out/1/flight.mcap");
  std::vector<std::string> resume = arguments;
  resume.push_back("--resume");
  const test::CliResult resumed = run_cli(resume, work.path());
  ASSERT_EQ(resumed.exit_status, 0) << resumed.err;
  EXPECT_EQ(read_whole_file(work / "out/1/flight.mcap"), member);
}

TEST(FlightMcap, BaseLinkHasRep103AxesAndTheSensorFrameTheMount) {
  // Heading 0° (north), level: base_link's x (forward) is map's north, its y (left) west, z up;
  // heading 90°: forward east, left north — map's own axes.
  Pose pose;
  pose.position_enu_m = {1, 2, 3};
  const ros2::TransformStamped tf = map_to_base_link(pose, {});
  EXPECT_EQ(tf.header.frame_id, "map");
  EXPECT_EQ(tf.child_frame_id, "base_link");
  EXPECT_EQ(tf.transform.translation.y, 2);
  const auto rotation = [](const ros2::Quaternion& q) {
    return Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
  };
  const Eigen::Matrix3d north = rotation(tf.transform.rotation);
  EXPECT_TRUE(north.isApprox(Eigen::Matrix3d{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, 1e-12)) << north;
  pose.attitude.heading_deg = 90;
  const Eigen::Matrix3d east = rotation(map_to_base_link(pose, {}).transform.rotation);
  EXPECT_TRUE(east.isApprox(Eigen::Matrix3d::Identity(), 1e-12)) << east;
  // Nose up 10°: forward climbs.
  pose.attitude.heading_deg = 0;
  pose.attitude.pitch_deg = 10;
  const auto& p = map_to_base_link(pose, {}).transform.rotation;
  const Eigen::Vector3d forward = rotation(p) * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(forward.z(), std::sin(10 * M_PI / 180), 1e-12);
  EXPECT_NEAR(forward.y(), std::cos(10 * M_PI / 180), 1e-12);  // north

  // Mount pitch −4° (looks down), lever arm 1 m forward, 0.5 m right, 0.2 m down.
  Mount mount;
  mount.pitch_deg = -4;
  mount.lever_arm_m = {1, 0.5, 0.2};
  const ros2::TransformStamped sensor = base_link_to_sensor(mount, {});
  EXPECT_EQ(sensor.header.frame_id, "base_link");
  EXPECT_EQ(sensor.child_frame_id, "owsim_sensor");
  EXPECT_EQ(sensor.transform.translation.x, 1);
  EXPECT_EQ(sensor.transform.translation.y, -0.5);
  EXPECT_EQ(sensor.transform.translation.z, -0.2);
  const auto& s = sensor.transform.rotation;
  const Eigen::Vector3d boresight = rotation(s) * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(boresight.z(), -std::sin(4 * M_PI / 180), 1e-12);
  EXPECT_NEAR(boresight.x(), std::cos(4 * M_PI / 180), 1e-12);
}

TEST(FlightMcap, AFlightBeforeTimeZeroIsShiftedByWholeSeconds) {
  ScanParams scan;
  scan.start_s = -2.5;
  const FlightMcapClock shifted(scan);
  EXPECT_EQ(shifted.time_offset_s(), 3);
  EXPECT_EQ(shifted.nanoseconds(-2.5), 500'000'000u);
  EXPECT_EQ(shifted.nanoseconds(1.25), 4'250'000'000u);
  EXPECT_THROW((void)shifted.nanoseconds(-3.5), Error);
  scan.start_s = 7.0;
  const FlightMcapClock plain(scan);
  EXPECT_EQ(plain.time_offset_s(), 0);
  EXPECT_EQ(plain.nanoseconds(7.0), 7'000'000'000u);
  const ros2::Time stamp = FlightMcapClock::stamp(4'250'000'000u);
  EXPECT_EQ(stamp.sec, 4);
  EXPECT_EQ(stamp.nanosec, 250'000'000u);
}

}  // namespace
}  // namespace owsim
