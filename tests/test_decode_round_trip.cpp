// Protects `owsim decode` end to end: `owsim run` with noise off, then `owsim decode` of its words,
// gives every return back — same frame, pulse, fiber, time and counter — within the counter's
// quantisation along the ray (Δ/2 = 0.30 m) and the mirror angle's quantisation across it (MilOWS
// encoder ±0.0018°, HELLAS NI ±0.0009°), for every example scenario, a HELLAS one, one whose time
// tags wrap and a recording cut mid-frame; and bad input fails with one line and no output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/hellas_scan.hpp"
#include "sensor/motor_encoder.hpp"
#include "sensor/mounting.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

using test::run_cli;
using test::TempDir;

constexpr int kFrames = 2;
constexpr double kCsvRounding_m = 2e-4;  // e, n, u and range_m are written to 0.1 mm

struct Row {
  std::string frame, pulse, line, fiber, ret, time;
  double range_m = 0;
  int counter = 0;
  Eigen::Vector3d enu = Eigen::Vector3d::Zero();
  std::string surface, object;
  std::string text;  // the whole line
};

using Key = std::tuple<long, long, int>;  // frame, pulse, return

std::map<Key, Row> read_points(const std::filesystem::path& path) {
  std::ifstream file(path);
  EXPECT_TRUE(file) << path;
  std::string line;
  std::getline(file, line);  // header
  std::map<Key, Row> rows;
  while (std::getline(file, line)) {
    std::vector<std::string> cells;
    std::stringstream stream(line);
    std::string cell;
    while (cells.size() < 16 && std::getline(stream, cell, ',')) cells.push_back(cell);
    EXPECT_GE(cells.size(), 16u) << line;
    if (cells.size() < 16) continue;
    Row row;
    row.frame = cells[0];
    row.pulse = cells[1];
    row.line = cells[2];
    row.fiber = cells[3];
    row.ret = cells[4];
    row.time = cells[5];
    row.range_m = std::stod(cells[6]);
    row.counter = std::stoi(cells[7]);
    row.enu = {std::stod(cells[8]), std::stod(cells[9]), std::stod(cells[10])};
    row.surface = cells[14];
    row.object = cells[15];
    row.text = line;
    rows[{std::stol(cells[0]), std::stol(cells[1]), std::stoi(cells[4])}] = row;
  }
  return rows;
}

// The largest error of the decoded mirror β, in radians  (SENSOR-SPEC §3 encoder, §8 NI mark)
double beta_error_rad(SensorModel model) {
  if (model == SensorModel::hellas) {
    return 0.5 * hellas_mirror_angle_factor_deg(ScanParams{}) * M_PI / 180.0 + 1e-12;
  }
  double slope = std::numeric_limits<double>::infinity();
  for (double beta = -30.0; beta <= 30.0; beta += 0.01) {
    slope = std::min(slope, std::abs(motor_angle_slope(beta)));
  }
  return 0.5 * kEncoderDegPerCount / slope * M_PI / 180.0 + 1e-12;
}

struct RoundTrip {
  std::size_t points = 0;
  double max_along_m = 0, max_lateral_m = 0, max_lateral_per_km_m = 0;
  double class_agreement = 1.0;
};

// Runs, decodes and compares; `scenario` may be anywhere (relative data paths resolve against it).
RoundTrip round_trip(const std::filesystem::path& scenario, const TempDir& dir) {
  RoundTrip result;
  const Scenario parsed = load_scenario(scenario);
  const bool milows = parsed.scan.model == SensorModel::milows;
  const std::string words = milows ? "run/flight.d64" : "run/flight.hellas";
  const auto run =
      run_cli({"run", scenario.string(), "--frames", std::to_string(kFrames), "--no-noise",
               "--outputs", "d64,points", "--out", "run", "--quiet", "--threads", "2"},
              dir.path());
  EXPECT_EQ(run.exit_status, 0) << run.command << "\n" << run.err;
  const auto decode = run_cli(
      {"decode", words, "--scenario", scenario.string(), "--out", "decoded", "--threads", "2"},
      dir.path());
  EXPECT_EQ(decode.exit_status, 0) << decode.command << "\n" << decode.err;
  EXPECT_NE(decode.err.find("on the scenario's pulse grid"), std::string::npos) << decode.err;

  const auto simulated = read_points(dir / "run/points.csv");
  const auto decoded = read_points(dir / "decoded/points.csv");
  EXPECT_GT(simulated.size(), 1000u) << scenario;
  EXPECT_EQ(decoded.size(), simulated.size()) << scenario;

  const LocalFrame local_frame(parsed.origin);
  const Trajectory trajectory = load_trajectory(parsed, local_frame);
  const double count_m = range_per_count_m(parsed.receiver.counter);
  const double beta_rad = beta_error_rad(parsed.scan.model);
  std::size_t same_class = 0;
  for (const auto& [key, sim] : simulated) {
    const auto found = decoded.find(key);
    if (found == decoded.end()) {
      ADD_FAILURE() << scenario << ": no decoded point for " << sim.text;
      continue;
    }
    const Row& dec = found->second;
    ++result.points;
    EXPECT_EQ(dec.counter, sim.counter) << sim.text;
    EXPECT_EQ(dec.time, sim.time) << sim.text;
    EXPECT_EQ(dec.line, sim.line) << sim.text;
    EXPECT_EQ(dec.fiber, sim.fiber) << sim.text;
    EXPECT_NEAR(dec.range_m, sim.counter * count_m, kCsvRounding_m) << dec.text;
    EXPECT_LE(std::abs(dec.range_m - sim.range_m), 0.5 * count_m + kCsvRounding_m) << sim.text;

    const Eigen::Vector3d origin =
        sensor_placement(trajectory.pose_at(std::stod(sim.time)), parsed.mount, parsed.scan.model)
            .origin_enu_m;
    const Eigen::Vector3d ray = (sim.enu - origin).normalized();
    const Eigen::Vector3d error = dec.enu - sim.enu;
    const double along = error.dot(ray);
    const double lateral = (error - along * ray).norm();
    EXPECT_LE(std::abs(along), 0.5 * count_m + kCsvRounding_m) << sim.text << "\n" << dec.text;
    EXPECT_LE(lateral, sim.range_m * beta_rad + kCsvRounding_m) << sim.text << "\n" << dec.text;
    result.max_along_m = std::max(result.max_along_m, std::abs(along));
    result.max_lateral_m = std::max(result.max_lateral_m, lateral);
    result.max_lateral_per_km_m =
        std::max(result.max_lateral_per_km_m, (lateral - kCsvRounding_m) / sim.range_m * 1000.0);
    if (dec.surface == sim.surface && dec.object == sim.object) ++same_class;
  }
  if (result.points > 0) {
    result.class_agreement = static_cast<double>(same_class) / static_cast<double>(result.points);
  }
  return result;
}

void report(const std::string& name, const RoundTrip& trip) {
  std::cout << name << ": " << trip.points << " points, along-ray ≤ " << trip.max_along_m
            << " m, lateral ≤ " << trip.max_lateral_m << " m (" << trip.max_lateral_per_km_m
            << " m per km of range), class and object agree on " << trip.class_agreement * 100
            << " %\n";
}

std::filesystem::path examples_dir() {
  return std::filesystem::path(OWSIM_SOURCE_DIR) / "examples";
}

// A copy of an example with one line of text replaced, beside the original (for its data paths).
std::filesystem::path variant(const std::string& example, const std::string& from,
                              const std::string& to, const TempDir& dir) {
  std::string text = test::read_whole_file(examples_dir() / (example + ".yaml"));
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  const auto path = dir / (example + "_variant.yaml");
  std::ofstream(path) << text;
  return path;
}

TEST(DecodeRoundTrip, EveryExampleComesBackWithinTheCounterQuantisation) {
  std::vector<std::filesystem::path> examples;
  for (const auto& entry : std::filesystem::directory_iterator(examples_dir())) {
    // Scenarios only: a sweep file (corridor_sweep.yaml) sits beside its base.
    if (entry.path().extension() == ".yaml" && !entry.path().stem().string().ends_with("_sweep")) {
      examples.push_back(entry.path());
    }
  }
  std::sort(examples.begin(), examples.end());
  ASSERT_FALSE(examples.empty());
  for (const auto& example : examples) {
    SCOPED_TRACE(example.string());
    const TempDir dir("owsim_round_trip");
    const RoundTrip trip = round_trip(example, dir);
    report(example.stem().string(), trip);
    EXPECT_GE(trip.class_agreement, 0.99);
  }
}

TEST(DecodeRoundTrip, HellasComesBackWithinTheCounterQuantisation) {
  const TempDir dir("owsim_round_trip_hellas");
  const RoundTrip trip =
      round_trip(variant("single_span", "model: milows", "model: hellas", dir), dir);
  report("single_span as HELLAS", trip);
  EXPECT_GE(trip.class_agreement, 0.99);
}

TEST(DecodeRoundTrip, RecordingWhoseTimeTagsWrapComesBack) {
  // start_s 6.4 s: the 16-bit tag (100 µs) wraps at 6.5536 s, inside the second frame.
  const TempDir dir("owsim_round_trip_wrap");
  const auto scenario = variant("single_span", "start_s: 0", "start_s: 6.4", dir);
  const RoundTrip trip = round_trip(scenario, dir);
  EXPECT_GE(trip.class_agreement, 0.99);
  const auto info = run_cli(
      {"decode", "run/flight.d64", "--scenario", scenario.string(), "--out", "again"}, dir.path());
  EXPECT_NE(info.err.find("wrapped 1 time"), std::string::npos) << info.err;
  // One point format on its own: the same bytes as with all three, and no other file.
  const auto las = run_cli({"decode", "run/flight.d64", "--scenario", scenario.string(), "--out",
                            "las_only", "--outputs", "las", "--quiet"},
                           dir.path());
  ASSERT_EQ(las.exit_status, 0) << las.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "las_only/points.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "las_only/points.ply"));
  EXPECT_TRUE(test::read_whole_file(dir / "las_only/points.las") ==
              test::read_whole_file(dir / "again/points.las"));
  const auto words = run_cli({"decode", "run/flight.d64", "--scenario", scenario.string(), "--out",
                              "bad", "--outputs", "d64"},
                             dir.path());
  EXPECT_NE(words.exit_status, 0);
  EXPECT_NE(words.err.find("decode writes points only"), std::string::npos) << words.err;
}

TEST(DecodeRoundTrip, RecordingCutMidFrameDecodesToTheSamePoints) {
  const TempDir dir("owsim_round_trip_cut");
  const auto scenario = examples_dir() / "single_span.yaml";
  (void)round_trip(scenario, dir);
  // Drop the first 7000 and the last 5003 words (mid-line at both ends).
  const std::string whole = test::read_whole_file(dir / "run/flight.d64");
  const std::size_t begin = 7000 * 8, end = whole.size() - 5003 * 8;
  std::ofstream(dir / "cut.d64", std::ios::binary) << whole.substr(begin, end - begin);
  const auto cut =
      run_cli({"decode", "cut.d64", "--scenario", scenario.string(), "--out", "cut"}, dir.path());
  ASSERT_EQ(cut.exit_status, 0) << cut.err;
  EXPECT_NE(cut.err.find("starts mid-frame: the first word is pulse 7000 of frame 0"),
            std::string::npos)
      << cut.err;
  EXPECT_NE(cut.err.find("stops mid-frame: the last word is pulse 15348 of frame 1"),
            std::string::npos)
      << cut.err;
  const auto full = read_points(dir / "decoded/points.csv");
  const auto part = read_points(dir / "cut/points.csv");
  std::size_t expected = 0;
  for (const auto& [key, row] : full) {
    const long pulse = std::get<0>(key) * 20352 + std::get<1>(key);
    if (pulse < 7000 || pulse >= 2 * 20352 - 5003) continue;
    ++expected;
    const auto found = part.find(key);
    ASSERT_NE(found, part.end()) << row.text;
    EXPECT_EQ(found->second.text, row.text);
  }
  EXPECT_EQ(part.size(), expected);
}

TEST(DecodeCli, TrajectoryOptionReplacesTheScenariosSource) {
  // The HellSim flight decoded against a copy of its scenario flying waypoints instead, with the
  // navigation file given on the command line: the same points as with the scenario's own.
  const TempDir dir("owsim_decode_trajectory");
  const auto scenario = examples_dir() / "hellsim_flight.yaml";
  const auto navigation = examples_dir() / "data/hellsim_turn_north.txt";
  ASSERT_TRUE(std::filesystem::exists(navigation));
  // Everything from `file:` up to `start_s:` becomes a waypoint plan (tick_s, heading and
  // smoothing apply to files only; the defaults are what the example sets).
  std::string text = test::read_whole_file(scenario);
  const auto from = text.find("  file: data/hellsim_turn_north.txt");
  const auto to = text.find("  start_s:");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  text.replace(from, to - from,
               "  waypoints:\n    speed_mps: 40\n    points:\n"
               "      - {e: 0, n: 0, u: 100}\n      - {e: 1000, n: 0, u: 100}\n");
  const auto waypoints = dir / "waypoints.yaml";
  std::ofstream(waypoints) << text;
  const auto run = run_cli({"run", scenario.string(), "--frames", "2", "--no-noise", "--outputs",
                            "d64", "--out", "run", "--quiet"},
                           dir.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const auto own = run_cli(
      {"decode", "run/flight.d64", "--scenario", scenario.string(), "--out", "own", "--quiet"},
      dir.path());
  ASSERT_EQ(own.exit_status, 0) << own.err;
  const auto given = run_cli({"decode", "run/flight.d64", "--scenario", waypoints.string(),
                              "--trajectory", navigation.string(), "--out", "given", "--quiet"},
                             dir.path());
  ASSERT_EQ(given.exit_status, 0) << given.err;
  EXPECT_GT(read_points(dir / "own/points.csv").size(), 1000u);
  EXPECT_TRUE(test::read_whole_file(dir / "own/points.csv") ==
              test::read_whole_file(dir / "given/points.csv"));

  const auto wrong =
      run_cli({"decode", "run/flight.d64", "--scenario", waypoints.string(), "--trajectory",
               navigation.string(), "--trajectory-format", "csv", "--out", "wrong"},
              dir.path());
  EXPECT_EQ(wrong.exit_status, 1) << wrong.err;
  EXPECT_EQ(std::count(wrong.err.begin(), wrong.err.end(), '\n'), 1) << wrong.err;
  EXPECT_NE(wrong.err.find("hellsim_turn_north.txt"), std::string::npos) << wrong.err;
}

TEST(DecodeCli, GarbageAndMismatchedInputFailWithOneLineAndNoOutput) {
  const TempDir dir("owsim_decode_cli");
  const auto scenario = (examples_dir() / "single_span.yaml").string();
  std::ofstream(dir / "garbage.d64") << "not a recording at all";  // 22 bytes: 2 words + 6
  const auto garbage =
      run_cli({"decode", "garbage.d64", "--scenario", scenario, "--out", "out"}, dir.path());
  EXPECT_EQ(garbage.exit_status, 1) << garbage.err;
  EXPECT_EQ(std::count(garbage.err.begin(), garbage.err.end(), '\n'), 1) << garbage.err;
  EXPECT_NE(garbage.err.find("garbage.d64"), std::string::npos) << garbage.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/points.csv"));

  std::ofstream(dir / "flight.hellas", std::ios::binary) << std::string(8, '\0');
  const auto mismatch =
      run_cli({"decode", "flight.hellas", "--scenario", scenario, "--out", "out"}, dir.path());
  EXPECT_EQ(mismatch.exit_status, 1) << mismatch.err;
  EXPECT_NE(mismatch.err.find("sensor.model milows"), std::string::npos) << mismatch.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/points.csv"));
}

}  // namespace
}  // namespace owsim
