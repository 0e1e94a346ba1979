// Protects issue 7's promise that owsim never silently writes wrong data: every bad input, run
// through the CLI, gives one stderr line naming the file and the line or key and the problem,
// exits non-zero, and leaves no output file in the output folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  ASSERT_TRUE(file.good()) << path;
}

void write_doubles(const fs::path& path, const std::vector<double>& values, std::size_t bytes) {
  std::vector<char> raw(values.size() * sizeof(double));
  std::memcpy(raw.data(), values.data(), raw.size());  // x86-64: little-endian as SBET is
  std::ofstream file(path, std::ios::binary);
  file.write(raw.data(), static_cast<std::streamsize>(std::min(bytes, raw.size())));
  ASSERT_TRUE(file.good()) << path;
}

// A valid scenario: a 1 s flight past one span (the runs stop after one frame); `trajectory` and
// `span` replace its blocks.
const std::string kWaypoints =
    "trajectory:\n"
    "  waypoints:\n"
    "    speed_mps: 40\n"
    "    points:\n"
    "      - {e: -100, n: 0, u: 60}\n"
    "      - {e: 100, n: 0, u: 60}\n"
    "  duration_s: 1\n";
const std::string kSpan =
    "    - id: line-a\n"
    "      from: {e: 0, n: -50}\n"
    "      to: {e: 0, n: 50}\n"
    "      support_heights_m: [30, 30]\n"
    "      lowest_point_m: 20\n"
    "      layout: single\n"
    "      conductor: {diameter_mm: 20, reflectivity: 0.4}\n";

std::string scenario(const std::string& trajectory = kWaypoints, const std::string& span = kSpan) {
  return "name: bad\n"
         "seed: 1\n"
         "origin: {lat: 48.6881, lon: 10.8447, h: 450.0}\n"
         "sensor: {model: milows}\n" +
         trajectory +
         "scene:\n"
         "  terrain: {flat_u: 0}\n"
         "  spans:\n" +
         span;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Every regular file under `dir` (none if it does not exist).
std::vector<std::string> files_under(const fs::path& dir) {
  std::vector<std::string> found;
  if (!fs::exists(dir)) return found;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) found.push_back(entry.path().string());
  }
  return found;
}

// The run failed with exit status ≠ 0 and exactly one stderr line "owsim: …" holding every
// fragment, and wrote nothing into `out`.
void expect_one_line_error(const CliResult& result, const std::vector<std::string>& fragments,
                           const fs::path& out) {
  SCOPED_TRACE(result.command);
  EXPECT_NE(result.exit_status, 0);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("owsim: ", 0), 0u) << result.err;
  EXPECT_EQ(result.err.find("internal error"), std::string::npos) << result.err;
  for (const std::string& fragment : fragments) {
    EXPECT_NE(result.err.find(fragment), std::string::npos)
        << "stderr lacks \"" << fragment << "\": " << result.err;
  }
  EXPECT_EQ(files_under(out), std::vector<std::string>{}) << result.err;
}

struct ScenarioCase {
  std::string name;
  std::string yaml;
  std::vector<std::string> fragments;  // besides the file name
};

class CliErrors : public ::testing::Test {
 protected:
  // `owsim run bad.yaml --out out` in the temporary folder.
  CliResult run_scenario(const std::string& yaml) {
    write_text(dir_ / "bad.yaml", yaml);
    return run_cli({"run", "bad.yaml", "--out", "out", "--frames", "1", "--quiet"}, dir_.path());
  }
  TempDir dir_{"owsim_cli_errors"};
};

TEST_F(CliErrors, TheValidScenarioRuns) {
  // The base the cases below break: it must itself run, or they would prove nothing.
  const CliResult result = run_scenario(scenario());
  EXPECT_EQ(result.exit_status, 0) << result.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "flight.d64")) << result.err;
}

TEST_F(CliErrors, BadScenariosNameFileLineAndKey) {
  const std::vector<ScenarioCase> cases = {
      {"malformed YAML", scenario() + "  - {id: [unclosed\n", {"bad.yaml:"}},
      {"unknown key",
       replaced(scenario(), "diameter_mm: 20", "diamter_mm: 20"),
       {"bad.yaml:21", "diamter_mm"}},
      {"wrong type",
       replaced(scenario(), "diameter_mm: 20", "diameter_mm: thick"),
       {"bad.yaml:21", "diameter_mm"}},
      {"negative size",
       replaced(scenario(), "diameter_mm: 20", "diameter_mm: -20"),
       {"bad.yaml:21", "diameter_mm"}},
      {"non-finite size",
       replaced(scenario(), "diameter_mm: 20", "diameter_mm: .nan"),
       {"bad.yaml:21", "diameter_mm"}},
      {"infinite size",
       replaced(scenario(), "support_heights_m: [30, 30]", "support_heights_m: [30, .inf]"),
       {"bad.yaml:18", "support_heights_m"}},
      {"sag above its supports",
       replaced(scenario(), "lowest_point_m: 20", "lowest_point_m: 35"),
       {"bad.yaml:", "spans[0]"}},
  };
  for (const ScenarioCase& bad : cases) {
    SCOPED_TRACE(bad.name);
    fs::remove_all(dir_ / "out");
    std::vector<std::string> fragments = bad.fragments;
    fragments.push_back("bad.yaml");
    expect_one_line_error(run_scenario(bad.yaml), fragments, dir_ / "out");
  }
}

std::string csv_trajectory(const std::string& file) {
  return "trajectory:\n"
         "  file: " +
         file +
         "\n"
         "  format: csv\n";
}

const std::string kCsvHeader = "time_s,lat_deg,lon_deg,h_m,roll_deg,pitch_deg,heading_deg\n";

TEST_F(CliErrors, TrajectoryWithNanNamesItsLine) {
  write_text(dir_ / "track.csv", kCsvHeader +
                                     "0.0,48.6881,10.8440,510,0,0,90\n"
                                     "0.1,48.6881,nan,510,0,0,90\n"
                                     "0.2,48.6881,10.8450,510,0,0,90\n");
  expect_one_line_error(run_scenario(scenario(csv_trajectory("track.csv"))), {"track.csv:3"},
                        dir_ / "out");
}

TEST_F(CliErrors, NonMonotonicTimeNamesItsLine) {
  write_text(dir_ / "track.csv", kCsvHeader +
                                     "0.0,48.6881,10.8440,510,0,0,90\n"
                                     "0.2,48.6881,10.8445,510,0,0,90\n"
                                     "0.1,48.6881,10.8450,510,0,0,90\n"
                                     "0.3,48.6881,10.8455,510,0,0,90\n");
  expect_one_line_error(run_scenario(scenario(csv_trajectory("track.csv"))), {"track.csv:4"},
                        dir_ / "out");
}

TEST_F(CliErrors, TruncatedSbetRecordNamesItsByte) {
  constexpr double kRad = 3.14159265358979323846 / 180.0;
  std::vector<double> values;
  for (int i = 0; i < 3; ++i) {
    const std::vector<double> record = {100.0 + 0.1 * i,
                                        48.6881 * kRad,
                                        (10.8440 + 0.0005 * i) * kRad,
                                        510,
                                        40,
                                        0,
                                        0,
                                        0,
                                        0,
                                        90 * kRad,
                                        0,
                                        0,
                                        0,
                                        0,
                                        0,
                                        0,
                                        0};
    values.insert(values.end(), record.begin(), record.end());
  }
  write_doubles(dir_ / "track.sbet", values, 2 * 136 + 50);  // the third record cut short
  const std::string trajectory =
      "trajectory:\n"
      "  file: track.sbet\n"
      "  format: sbet\n";
  expect_one_line_error(run_scenario(scenario(trajectory)),
                        {"track.sbet", "truncated record at byte 272"}, dir_ / "out");
}

TEST_F(CliErrors, InfoReportsARecordingOfPartialWords) {
  // 3 whole MilOWS words and 5 bytes of a fourth: a problem in the report, exit status 1.
  write_text(dir_ / "cut.d64", std::string(3 * 8 + 5, '\0'));
  const CliResult result = run_cli({"info", "cut.d64"}, dir_.path());
  EXPECT_NE(result.exit_status, 0);
  EXPECT_NE(result.out.find("5 trailing byte"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("word 3"), std::string::npos) << result.out;
}

struct CutRecording {
  std::string model;       // the scenario's sensor.model
  std::string file;        // what `owsim run` writes for it
  std::string word_bytes;  // its word size
  std::string trailing;    // what is left of the last word once 3 bytes are cut off
};

TEST_F(CliErrors, DecodeAndMergeRefuseARecordingOfPartialWords) {
  // A sound one-frame recording from `owsim run`, cut 3 bytes short of its last whole word.
  for (const CutRecording& cut :
       {CutRecording{"milows", "flight.d64", "8", "5 trailing bytes"},
        CutRecording{"hellas", "flight.hellas", "4", "1 trailing byte"}}) {
    SCOPED_TRACE(cut.model);
    write_text(dir_ / "rec.yaml", replaced(scenario(), "model: milows", "model: " + cut.model));
    const CliResult run =
        run_cli({"run", "rec.yaml", "--out", "rec", "--frames", "1", "--outputs", "d64", "--quiet"},
                dir_.path());
    ASSERT_EQ(run.exit_status, 0) << run.err;
    const fs::path recording = dir_ / "rec" / cut.file;
    const std::uintmax_t bytes = fs::file_size(recording) - 3;
    fs::resize_file(recording, bytes);
    const std::string name = "rec/" + cut.file;
    const std::string line = "owsim: " + name + ": cannot decode: " + std::to_string(bytes) +
                             " bytes is not a whole number of " + cut.word_bytes + "-byte words (" +
                             cut.trailing + ")\n";

    const CliResult decode =
        run_cli({"decode", name, "--scenario", "rec.yaml", "--out", "out", "--quiet"}, dir_.path());
    expect_one_line_error(decode, {}, dir_ / "out");
    EXPECT_EQ(decode.err, line);

    const CliResult merge =
        run_cli({"merge", name, "--scenario", "rec.yaml", "--out",
                 "out/merged" + fs::path(cut.file).extension().string(), "--quiet"},
                dir_.path());
    expect_one_line_error(merge, {}, dir_ / "out");
    EXPECT_EQ(merge.err, line);
  }
}

TEST_F(CliErrors, UnwritableOutputFolderIsOneLine) {
  // A regular file where the output folder should be: no user, root included, can write there.
  write_text(dir_ / "blocker", "not a folder\n");
  write_text(dir_ / "good.yaml", scenario());
  const CliResult result = run_cli(
      {"run", "good.yaml", "--out", "blocker/out", "--frames", "1", "--quiet"}, dir_.path());
  expect_one_line_error(result, {"blocker"}, dir_ / "blocker" / "out");
  EXPECT_EQ(test::read_whole_file(dir_ / "blocker"), "not a folder\n");
}

TEST_F(CliErrors, MissingImageModuleIsOneLineBeforeAnythingIsWritten) {
  // Quick-look images need the optional module libowsim_png.so (OpenImageIO); where it cannot be
  // loaded, the run says so at once and leaves no output behind. Words alone still run.
  write_text(dir_ / "good.yaml", scenario());
  ASSERT_EQ(::setenv("OWSIM_MODULE_DIR", (dir_ / "no_modules").c_str(), 1), 0);
  const CliResult images = run_cli({"run", "good.yaml", "--out", "out", "--frames", "1",
                                    "--outputs", "d64,quicklook", "--quiet"},
                                   dir_.path());
  const CliResult words = run_cli(
      {"run", "good.yaml", "--out", "words", "--frames", "1", "--outputs", "d64", "--quiet"},
      dir_.path());
  ::unsetenv("OWSIM_MODULE_DIR");
  expect_one_line_error(images, {"quick-look images", "libowsim_png.so", "no_modules"},
                        dir_ / "out");
  EXPECT_EQ(words.exit_status, 0) << words.err;
  EXPECT_TRUE(fs::exists(dir_ / "words" / "flight.d64"));
}

TEST_F(CliErrors, SeedsThatWouldWrapAreRefused) {
  // CLI11 alone read -1 as 2^64 - 1 and 2^64 as 0: two seeds ran as one.
  write_text(dir_ / "good.yaml", scenario());
  for (const std::string seed : {"-1", "18446744073709551616", "1e3"}) {
    const CliResult result =
        run_cli({"run", "good.yaml", "--out", "out", "--frames", "1", "--seed", seed, "--quiet"},
                dir_.path());
    expect_one_line_error(result, {"--seed", "18446744073709551615", seed}, dir_ / "out");
  }
}

TEST_F(CliErrors, AFlightOrObjectFarFromTheOriginIsRefusedBeforeTheRayTracer) {
  // Positions far from the origin reached Embree (floats) and aborted it; a waypoint or a pole
  // given in lat/lon is within every key's range yet thousands of km from the origin.
  const std::string far_flight =
      "trajectory:\n"
      "  waypoints:\n"
      "    speed_mps: 40\n"
      "    points:\n"
      "      - {lat: 10, lon: 10, h: 100}\n"
      "      - {lat: 10.01, lon: 10, h: 100}\n"
      "  duration_s: 1\n";
  CliResult result = run_scenario(scenario(far_flight));
  expect_one_line_error(result,
                        {"bad.yaml: trajectory.waypoints: the flight at t = 0 s",
                         "m from the "
                         "scenario origin",
                         "within 200000 m"},
                        dir_ / "out");
  const std::string far_pole = kSpan +
                               "  poles:\n    - {id: far, at: {lat: 10, lon: 10}, "
                               "height_m: 10, diameter_m: 1}\n";
  result = run_scenario(scenario(kWaypoints, far_pole));
  expect_one_line_error(result, {"scene object 'far'", "m from the scenario origin"}, dir_ / "out");
}

}  // namespace
}  // namespace owsim
