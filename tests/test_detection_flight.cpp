// Protects the reference detector end to end (issue 69, DETECTION-SPEC, INTERFACE.md "Obstacle
// warnings"): on the acceptance approach (tests/data/detector/approach.yaml) every conductor is
// warned as a wire at least 15 s before the aircraft reaches it, the mast as a pole, the tree and
// the building as trees, for several seeds; `owsim detect` writes the bytes the run wrote, for any
// thread count, from the words and the navigation alone (the scene taken out of the scenario); and
// bad input is refused in one line with nothing written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "cli_runner.hpp"
#include "csv_rows.hpp"

namespace owsim {
namespace {

using test::CliResult;
using test::csv_rows;
using test::read_whole_file;
using test::run_cli;
using test::TempDir;

const std::string kApproach = OWSIM_SOURCE_DIR "/tests/data/detector/approach.yaml";

// Which of the approach's objects a warning is of, by where its nearest point lies: the three
// conductors at e = −4, 0, 4 m between 25 and 29 m up (away from the support poles at n = ±250 m,
// whose clusters hold the conductors' ends), the mast at (−300, 60), the tree at
// (−600, −70), the building's box around (−900, 80).
std::optional<std::string> object_of(double e, double n, double u) {
  for (const double conductor : {-4.0, 0.0, 4.0}) {
    if (std::abs(e - conductor) < 1.5 && u > 20.0 && u < 32.0 && std::abs(n) < 200.0) {
      return "conductor " + std::to_string(static_cast<int>(conductor));
    }
  }
  if (std::hypot(e + 300.0, n - 60.0) < 3.0) return "mast";
  if (std::hypot(e + 600.0, n + 70.0) < 6.0) return "tree";
  if (e > -913.0 && e < -887.0 && n > 69.0 && n < 91.0) return "building";
  return std::nullopt;
}

struct ObjectWarnings {
  std::optional<double> first_right_s;  // the first warning of its class
  int warned = 0;                       // frames with a warning of it
  int right = 0;                        // … of its class
};

std::map<std::string, ObjectWarnings> warnings_by_object(const std::filesystem::path& csv) {
  const auto rows = csv_rows(csv);
  EXPECT_FALSE(rows.empty());
  const auto& header = rows.front();
  const std::size_t t = test::column(header, "time_s"), c = test::column(header, "class"),
                    e = test::column(header, "e_m"), n = test::column(header, "n_m"),
                    u = test::column(header, "u_m");
  const std::map<std::string, std::string> right_class = {
      {"conductor -4", "wire"}, {"conductor 0", "wire"}, {"conductor 4", "wire"},
      {"mast", "pole"},         {"tree", "tree"},        {"building", "tree"}};
  std::map<std::string, ObjectWarnings> out;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto& row = rows[r];
    const std::optional<std::string> object =
        object_of(std::stod(row[e]), std::stod(row[n]), std::stod(row[u]));
    if (!object) continue;
    ObjectWarnings& seen = out[*object];
    ++seen.warned;
    if (row[c] != right_class.at(*object)) continue;
    ++seen.right;
    if (!seen.first_right_s) seen.first_right_s = std::stod(row[t]);
  }
  return out;
}

TEST(DetectionFlight, EveryObstacleIsWarnedAsItsClassInTime) {
  for (const std::string seed : {"1", "2", "3"}) {
    SCOPED_TRACE("seed " + seed);
    const TempDir dir;
    const CliResult run = run_cli({"run", kApproach, "--seed", seed, "--out", "out", "--outputs",
                                   "detections", "--quiet"},
                                  dir.path());
    ASSERT_EQ(run.exit_status, 0) << run.err;
    const auto seen = warnings_by_object(dir / "out/detections.csv");
    for (const std::string object : {"conductor -4", "conductor 0", "conductor 4", "mast", "tree",
                                     "building"}) {
      SCOPED_TRACE(object);
      ASSERT_TRUE(seen.contains(object));
      const ObjectWarnings& w = seen.at(object);
      ASSERT_TRUE(w.first_right_s.has_value());
      // Nine in ten of the frames that warn of it give its class.
      EXPECT_GE(w.right, 0.9 * w.warned) << w.right << " of " << w.warned;
      // The aircraft reaches the span after 35 s (1,400 m at 40 m/s): warned by 20 s.
      if (object.starts_with("conductor")) EXPECT_LE(*w.first_right_s, 20.0);
    }
  }
}

TEST(DetectionFlight, DetectWritesTheBytesTheRunWroteFromWordsAndNavigationAlone) {
  const TempDir dir;
  for (const std::string threads : {"1", "2"}) {
    const CliResult run = run_cli({"run", kApproach, "--out", "t" + threads, "--threads", threads,
                                   "--outputs", "d64,truth,detections", "--quiet"},
                                  dir.path());
    ASSERT_EQ(run.exit_status, 0) << run.err;
  }
  const std::string in_loop = read_whole_file(dir / "t1/detections.csv");
  ASSERT_GT(in_loop.size(), 10000u);
  EXPECT_EQ(read_whole_file(dir / "t2/detections.csv"), in_loop);

  const CliResult detect = run_cli({"detect", "t1", "--out", "again"}, dir.path());
  ASSERT_EQ(detect.exit_status, 0) << detect.err;
  EXPECT_EQ(read_whole_file(dir / "again/detections.csv"), in_loop);

  // The words and the scenario without its scene: no object, class, energy or incidence to read.
  std::filesystem::create_directory(dir / "bare");
  std::filesystem::copy_file(dir / "t1/flight.d64", dir / "bare/flight.d64");
  std::ifstream flown(dir / "t1/scenario.yaml");
  std::ofstream bare(dir / "bare/scenario.yaml");
  std::string line;
  bool in_scene = false;
  while (std::getline(flown, line)) {
    if (!line.empty() && line[0] != ' ' && line[0] != '-') in_scene = line.starts_with("scene:");
    if (!in_scene) bare << line << '\n';
  }
  bare << "scene: {terrain: none}\n";
  bare.close();
  const CliResult blind = run_cli({"detect", "bare", "--quiet"}, dir.path());
  ASSERT_EQ(blind.exit_status, 0) << blind.err;
  EXPECT_EQ(read_whole_file(dir / "bare/detections.csv"), in_loop);
}

nlohmann::json read_json(const std::filesystem::path& file) {
  return nlohmann::json::parse(read_whole_file(file));
}

// detections.csv with each row changed by `change` (cells by column).
void rewrite_rows(const std::filesystem::path& from, const std::filesystem::path& to,
                  const std::function<void(std::vector<std::string>&)>& change) {
  const auto rows = csv_rows(from);
  std::ofstream out(to);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::vector<std::string> cells = rows[r];
    if (r > 0) change(cells);
    for (std::size_t c = 0; c < cells.size(); ++c) out << (c ? "," : "") << cells[c];
    out << '\n';
  }
}

// `owsim pd --detections`: the warnings are the evidence (a window is detected when a frame of it
// warned of the target with its class, DETECTION-SPEC §5). On the approach every conductor is
// warned, so the three trials are detected; the same warnings relabelled `pole` warn of no wire;
// moved 200 m off every object they are false warnings, one per track. Without --detections pd.json
// is the returns' as before. `owsim roc --detections` over a sweep of two thresholds.
TEST(DetectionFlight, WarningPdCountsTheWindowsWarningsOfTheTargetsClassMatched) {
  const TempDir dir;
  ASSERT_EQ(run_cli({"run", kApproach, "--out", "run", "--outputs", "d64,summary,truth,detections",
                     "--quiet"},
                    dir.path())
                .exit_status,
            0);
  const CliResult returns = run_cli({"pd", "run", "--out", "returns", "--quiet"}, dir.path());
  ASSERT_EQ(returns.exit_status, 0) << returns.err;
  const CliResult warned =
      run_cli({"pd", "run", "--detections", "run", "--out", "warned", "--quiet"}, dir.path());
  ASSERT_EQ(warned.exit_status, 0) << warned.err;
  const nlohmann::json by_returns = read_json(dir / "returns/pd.json");
  const nlohmann::json by_warnings = read_json(dir / "warned/pd.json");
  EXPECT_FALSE(by_returns.contains("evidence"));
  EXPECT_EQ(by_warnings.at("evidence"), "warnings");
  EXPECT_EQ(by_warnings.at("trials"), 3);
  EXPECT_EQ(by_warnings.at("trials_detected"), 3);
  // The same windows; the warnings detect fewer of them than the returns at range.
  EXPECT_EQ(by_warnings.at("windows"), by_returns.at("windows"));
  EXPECT_GT(by_warnings.at("windows_detected").get<int>(), 0);
  // Every track on the approach warns of an object: no false warning.
  EXPECT_EQ(by_warnings.at("false_warnings"), 0);
  EXPECT_GT(by_warnings.at("warning_tracks").get<int>(), 5);
  EXPECT_NEAR(by_warnings.at("flight_hours").get<double>(), 36.0 / 3600.0, 0.5 / 3600.0);

  // pd.json of the approach's detections changed row by row by `change`.
  const auto pd_of_changed = [&](const std::string& name,
                                 const std::function<void(std::vector<std::string>&)>& change) {
    rewrite_rows(dir / "run/detections.csv", dir / (name + ".csv"), change);
    const CliResult pd = run_cli(
        {"pd", "run", "--detections", name + ".csv", "--out", name, "--quiet"}, dir.path());
    EXPECT_EQ(pd.exit_status, 0) << pd.err;
    return read_json(dir / name / "pd.json");
  };
  // Relabelled: no wire warned.
  const nlohmann::json by_poles =
      pd_of_changed("poles", [](std::vector<std::string>& cells) { cells[3] = "pole"; });
  EXPECT_EQ(by_poles.at("windows_detected"), 0);
  EXPECT_EQ(by_poles.at("false_warnings"), 0);
  // Moved 200 m up: every track is a false warning.
  const nlohmann::json moved = pd_of_changed("moved", [](std::vector<std::string>& cells) {
    cells[6] = std::to_string(std::stod(cells[6]) + 200.0);
  });
  EXPECT_EQ(moved.at("windows_detected"), 0);
  EXPECT_EQ(moved.at("false_warnings"), by_warnings.at("warning_tracks"));

  // A missing detections file: one line naming it, nothing written.
  const CliResult missing =
      run_cli({"pd", "run", "--detections", "nowhere.csv", "--out", "none"}, dir.path());
  EXPECT_NE(missing.exit_status, 0);
  EXPECT_NE(missing.err.find("nowhere.csv: missing"), std::string::npos) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "none"));
}

TEST(DetectionFlight, WarningRocPlotsTheWarningPdAgainstFalseWarningsPerHour) {
  const TempDir dir;
  std::filesystem::copy_file(kApproach, dir / "approach.yaml");
  std::filesystem::copy_file(OWSIM_SOURCE_DIR "/tests/data/detector/building.obj",
                             dir / "building.obj");
  std::ofstream(dir / "sweep.yaml") << "base: approach.yaml\ncount: 2\nseed: 3\n"
                                       "outputs: summary,truth,detections\n"
                                       "vary:\n  sensor.threshold: {values: [0.002, 0.004]}\n";
  const CliResult sweep =
      run_cli({"sweep", "sweep.yaml", "--out", "campaign", "--quiet"}, dir.path());
  ASSERT_EQ(sweep.exit_status, 0) << sweep.err;
  const CliResult roc = run_cli({"roc", "campaign", "--range", "0:1300", "--detections",
                                 "campaign", "--out", "roc", "--quiet"},
                                dir.path());
  ASSERT_EQ(roc.exit_status, 0) << roc.err;
  const nlohmann::json report = read_json(dir / "roc/roc.json");
  EXPECT_EQ(report.at("evidence"), "warnings");
  ASSERT_EQ(report.at("rows").size(), 2u);
  for (const nlohmann::json& row : report.at("rows")) {
    EXPECT_GT(row.at("windows_detected").get<int>(), 0);
    EXPECT_DOUBLE_EQ(row.at("false_warnings_per_hour").get<double>(),
                     row.at("false_warnings").get<double>() / row.at("flight_hours").get<double>());
  }
  // 0.002 instead of the default 0.0029 lets ~3,500 false returns a second through: they cost
  // false warnings (and buy Pd); near the default there are none.
  const nlohmann::json& low = report.at("rows")[0];
  const nlohmann::json& high = report.at("rows")[1];
  EXPECT_EQ(low.at("value"), 0.002);
  EXPECT_GT(low.at("false_warnings").get<int>(), 10);
  EXPECT_EQ(high.at("false_warnings"), 0);
  EXPECT_GE(low.at("windows_detected").get<int>(), high.at("windows_detected").get<int>());
  const std::string header = read_whole_file(dir / "roc/roc.csv").substr(0, 200);
  EXPECT_NE(header.find(",false_warnings,flight_h,false_warnings_per_h\n"), std::string::npos);
  EXPECT_NE(read_whole_file(dir / "roc/roc.svg").find("false warnings per flight hour"),
            std::string::npos);
}

TEST(DetectionFlight, BadInputIsOneLineAndNothingWritten) {
  const TempDir dir;
  const auto refused = [&](const std::vector<std::string>& arguments, const std::string& says) {
    const CliResult result = run_cli(arguments, dir.path());
    EXPECT_NE(result.exit_status, 0) << result.command;
    EXPECT_NE(result.err.find(says), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  };
  refused({"detect", "missing"}, "missing: not a folder");
  std::filesystem::create_directory(dir / "empty");
  refused({"detect", "empty"}, "empty: not a run folder");
  EXPECT_TRUE(std::filesystem::is_empty(dir / "empty"));

  // A run folder whose words are gone, or cut inside a word.
  ASSERT_EQ(run_cli({"run", kApproach, "--out", "run", "--frames", "6", "--outputs", "d64",
                     "--quiet"},
                    dir.path())
                .exit_status,
            0);
  std::filesystem::rename(dir / "run/flight.d64", dir / "flight.d64");
  refused({"detect", "run"}, "run/flight.d64: missing");
  std::filesystem::copy_file(dir / "flight.d64", dir / "run/flight.d64");
  std::filesystem::resize_file(dir / "run/flight.d64",
                               std::filesystem::file_size(dir / "flight.d64") - 3);
  refused({"detect", "run"}, "run/flight.d64: cannot decode");
  EXPECT_FALSE(std::filesystem::exists(dir / "run/detections.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "run/detections.csv.partial"));

  // A detector value out of its range, at its file, line and key.
  std::ifstream approach(kApproach);
  std::ofstream bad(dir / "bad.yaml");
  std::string line;
  while (std::getline(approach, line)) {
    bad << (line.starts_with("detector:") ? "detector: {window_s: 0}" : line) << '\n';
  }
  bad.close();
  std::filesystem::copy_file(OWSIM_SOURCE_DIR "/tests/data/detector/building.obj",
                             dir / "building.obj");
  refused({"run", "bad.yaml", "--out", "bad", "--outputs", "detections"},
          "bad.yaml:40: detector.window_s: must be in [0.01, 60] s, got 0");
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
}

}  // namespace
}  // namespace owsim
