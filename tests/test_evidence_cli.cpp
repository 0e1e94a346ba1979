// Protects the detection evidence end to end (INTERFACE.md "Ground truth and detection evidence"):
// truth.csv counts every return points.csv holds on each object; a run folder's scenario.yaml
// flies the same bytes again; truth.csv alone equals the full run's; `owsim pd` over a sweep
// agrees with an independent recount (tests/oracles/pd_oracle.py: numpy counts, scipy's beta
// quantiles to 1e-9); physics: with no noise a head-on 5 mm wire is never detected beyond
// max_detection_range_m and always within it once the wire spans HELLAS's whole scan line; `owsim
// score` matches hand-placed detections (ENU and WGS-84 alike) to the nearest object within the
// gate, and the whole loop — sweep, the reference detector, score — runs; bad criteria, folders
// and detection files are refused in one line with nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "csv_rows.hpp"
#include "evaluation/truth_table.hpp"
#include "geometry/geodetic_frame.hpp"
#include "owsim/simulation.hpp"
#include "python_oracle.hpp"
#include "sensor/receiver.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::column;
using test::csv_rows;
using test::run_cli;
using test::TempDir;

const fs::path kSource = OWSIM_SOURCE_DIR;

TEST(EvidenceCli, TruthCountsEveryReturnAndTheFolderFliesAgainToTheSameBytes) {
  const TempDir work("owsim_evidence");
  const auto run = run_cli({"run", (kSource / "examples/pylon_line.yaml").string(), "--out", "a",
                            "--duration", "8", "--quiet"},
                           work.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  // Returns per object: points.csv against truth.csv.
  std::map<std::string, std::uint64_t> from_points, from_truth;
  const auto points = csv_rows(work / "a/points.csv");
  const std::size_t object = column(points.front(), "object");
  for (std::size_t r = 1; r < points.size(); ++r) {
    const std::string& id = points[r][object];
    if (id != "terrain" && !id.empty()) ++from_points[id];
  }
  const auto truth = csv_rows(work / "a/truth.csv");
  ASSERT_EQ(truth.front().size(), 11u);
  const std::size_t truth_object = column(truth.front(), "object");
  const std::size_t returns = column(truth.front(), "returns");
  const std::size_t in_view = column(truth.front(), "in_view");
  std::uint64_t rows_in_view = 0;
  for (std::size_t r = 1; r < truth.size(); ++r) {
    const std::uint64_t n = std::stoull(truth[r][returns]);
    if (n > 0) from_truth[truth[r][truth_object]] += n;
    rows_in_view += truth[r][in_view] == "1";
    // Returns on an object out of view can only come from the field's edge (one pose a frame).
  }
  EXPECT_GT(from_points.size(), 5u);
  EXPECT_EQ(from_truth, from_points);
  EXPECT_GT(rows_in_view, 100u);

  // scenario.yaml flies the same frames to the same bytes, from another folder.
  ASSERT_TRUE(fs::exists(work / "a/scenario.yaml"));
  fs::create_directories(work / "elsewhere");
  const auto again = run_cli(
      {"run", (work / "a/scenario.yaml").string(), "--out", "../b", "--quiet"}, work / "elsewhere");
  ASSERT_EQ(again.exit_status, 0) << again.err;
  for (const char* name :
       {"flight.d64", "points.csv", "truth.csv", "trajectory.csv", "scenario.yaml"}) {
    EXPECT_EQ(test::read_whole_file(work / "a" / name), test::read_whole_file(work / "b" / name))
        << name;
  }
  // truth alone equals the full run's.
  const auto alone = run_cli({"run", (kSource / "examples/pylon_line.yaml").string(), "--out", "c",
                              "--duration", "8", "--outputs", "truth", "--quiet"},
                             work.path());
  ASSERT_EQ(alone.exit_status, 0) << alone.err;
  EXPECT_EQ(test::read_whole_file(work / "c/truth.csv"),
            test::read_whole_file(work / "a/truth.csv"));
  EXPECT_FALSE(fs::exists(work / "c/flight.d64"));
}

TEST(EvidenceCli, PdOverASweepAgreesWithAnIndependentRecount) {
  const TempDir work("owsim_evidence_pd");
  // A sweep file reads only its own folder tree: the base is copied beside it.
  fs::copy_file(kSource / "examples/campaigns/hellas_5mm_approach.yaml",
                work / "hellas_5mm_approach.yaml");
  std::ofstream(work / "sweep.yaml")
      << "base: hellas_5mm_approach.yaml\n"
      << "count: 6\nseed: 3\noutputs: summary,truth\nvary:\n"
      << "  trajectory.waypoints.points[0].n: {uniform: [-300, 300]}\n"
      << "  trajectory.waypoints.points[0].e: {uniform: [-800, -600]}\n"
      << "  trajectory.waypoints.speed_mps: {uniform: [50, 70]}\n"
      << "  seed: {member: true}\n";
  const auto sweep = run_cli({"sweep", "sweep.yaml", "--out", "campaign", "--quiet"}, work.path());
  ASSERT_EQ(sweep.exit_status, 0) << sweep.err;
  const auto pd = run_cli({"pd", "campaign", "--target", "wire/1", "--bins", "0:900:75",
                           "--window-s", "0.7", "--returns", "2", "--quiet"},
                          work.path());
  ASSERT_EQ(pd.exit_status, 0) << pd.err;
  for (const char* name : {"pd.csv", "pd.json", "pd.svg"}) {
    EXPECT_TRUE(fs::exists(work / "campaign" / name)) << name;
  }
  const std::string oracle = test::run_python_file(
      kSource / "tests/oracles/pd_oracle.py",
      {.arguments = (work / "campaign").string() + " " + (work / "campaign/pd.csv").string() +
                    " 2 0.7 0 900 75 0.95 wire/1"});
  EXPECT_NE(oracle.find("agree"), std::string::npos) << oracle;
  // The class pooled, default criterion, into another folder, at another confidence.
  const auto pooled = run_cli(
      {"pd", "campaign", "--class", "wire", "--confidence", "0.9", "--out", "pooled", "--quiet"},
      work.path());
  ASSERT_EQ(pooled.exit_status, 0) << pooled.err;
  const std::string pooled_oracle = test::run_python_file(
      kSource / "tests/oracles/pd_oracle.py",
      {.arguments = (work / "campaign").string() + " " + (work / "pooled/pd.csv").string() +
                    " 1 1 0 1300 50 0.9 class:wire"});
  EXPECT_NE(pooled_oracle.find("agree"), std::string::npos) << pooled_oracle;
  const std::string json = test::read_whole_file(work / "pooled/pd.json");
  EXPECT_NE(json.find("\"interval\": \"clopper-pearson\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"trials\": 6"), std::string::npos) << json;
}

TEST(EvidenceCli, AHeadOnFiveMillimetreWireIsDetectedExactlyWithinTheModelsRange) {
  const TempDir work("owsim_evidence_physics");
  const fs::path base = kSource / "examples/campaigns/hellas_5mm_approach.yaml";
  const auto run =
      run_cli({"run", base.string(), "--out", "head_on", "--no-noise", "--quiet"}, work.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const Simulation simulation = Simulation::open(base);
  const double max_range = max_detection_range_m(0.005, 0.4, simulation.scenario().receiver);
  ASSERT_NEAR(max_range, 834.2, 0.1);  // README "What the default sensor detects" (T = 0.0029)
  // The wire spans HELLAS's whole line (α ±21°) nearer than 1,000 m / tan 21° from its middle.
  const std::vector<ObjectTrack> tracks =
      read_truth_csv(work / "head_on/truth.csv", read_flight_facts(work / "head_on/summary.json"),
                     [](std::string_view id, std::string_view) { return id == "wire/1"; });
  ASSERT_EQ(tracks.size(), 1u);
  // Half a frame of flight (50 m/s × 1/6 s) between a pulse and the frame's middle.
  const double margin_m = 50.0 / 6.0 + 1.0;
  int detected_frames = 0;
  for (const TruthEntry& row : tracks.front().rows) {
    ASSERT_TRUE(row.in_view || row.range_m < 60.0) << row.frame;
    if (row.range_m > max_range + margin_m) EXPECT_EQ(row.returns, 0u) << row.frame;
    if (row.range_m < max_range - margin_m && row.range_m > 80.0) {
      EXPECT_GE(row.returns, 1u) << row.frame << " at " << row.range_m << " m";
    }
    detected_frames += row.returns > 0;
  }
  EXPECT_GT(detected_frames, 20);
  // Every wire return lies within the model's range (no noise: counter steps of 0.6 m).
  const auto points = csv_rows(work / "head_on/points.csv");
  const std::size_t range = column(points.front(), "range_m");
  const std::size_t object = column(points.front(), "object");
  for (std::size_t r = 1; r < points.size(); ++r) {
    if (points[r][object] != "wire/1") continue;
    EXPECT_LE(std::stod(points[r][range]), max_range + 0.6) << r;
  }
}

TEST(EvidenceCli, BadCriteriaAndFoldersAreRefusedInOneLineWithNothingWritten) {
  const TempDir work("owsim_evidence_errors");
  const auto run = run_cli({"run", (kSource / "examples/single_span.yaml").string(), "--out", "r",
                            "--duration", "2", "--outputs", "summary,truth", "--quiet"},
                           work.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const auto refused = [&](std::vector<std::string> arguments, const std::string& starts) {
    const auto result = run_cli(arguments, work.path());
    EXPECT_NE(result.exit_status, 0) << result.command;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.err.rfind("owsim: " + starts, 0), 0u) << result.err;
    EXPECT_FALSE(fs::exists(work / "r/pd.csv")) << result.command;
  };
  refused({"pd", "r", "--bins", "100:50:10"}, "--bins");
  refused({"pd", "r", "--bins", "0:1300"}, "--bins");
  refused({"pd", "r", "--confidence", "1.5"}, "--confidence");
  refused({"pd", "r", "--window-s", "-1"}, "--window-s");
  refused({"pd", "r", "--target", "nothing"}, "--target");
  refused({"pd", "r", "--class", "cloud"}, "--class");
  refused({"pd", "missing"}, "missing");
  fs::remove(work / "r/truth.csv");
  refused({"pd", "r"}, (work / "r/truth.csv").string().substr(0, 0) + "r/truth.csv");
  std::ofstream(work / "r/truth.csv") << "frame,time_s\n";
  refused({"pd", "r"}, "r/truth.csv:1");
}

nlohmann::json read_json(const fs::path& path) {
  return nlohmann::json::parse(test::read_whole_file(path));
}

const nlohmann::json& object_entry(const nlohmann::json& score, const std::string& id) {
  for (const nlohmann::json& object : score.at("objects")) {
    if (object.at("id") == id) return object;
  }
  static const nlohmann::json none;
  ADD_FAILURE() << "no object " << id;
  return none;
}

TEST(EvidenceCli, ScoreMatchesEachDetectionToTheNearestObjectWithinTheGate) {
  const TempDir work("owsim_evidence_score");
  const auto run = run_cli({"run", (kSource / "examples/pylon_line.yaml").string(), "--out", "r",
                            "--duration", "8", "--outputs", "summary,truth", "--quiet"},
                           work.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  // pylon-2 stands at (0, 0), 3 m wide and 50 m tall; pylon-1 at (−150, −400); the conductors
  // hang from their tops.
  const Eigen::Vector3d beside_pylon_2(3.5, 0.0, 30.0);        // 2 m from its surface
  const Eigen::Vector3d in_the_sky(0.0, 0.0, 300.0);           // nothing within 5 m
  const Eigen::Vector3d beside_pylon_1(-146.5, -400.0, 10.0);  // below the conductors
  std::ofstream(work / "enu.csv") << "time_s,e_m,n_m,u_m,class,track,ignored\n"
                                  << "2.0,3.5,0,30,pole,a,x\n3.0,0,0,300,wire,,\n"
                                  << "4.0,-146.5,-400,10,pole,b,\n";
  const LocalFrame frame({48.6881, 10.8447, 450.0});
  {
    std::ofstream geodetic(work / "wgs84.csv");
    geodetic.precision(12);
    geodetic << "track,lat_deg,lon_deg,h_m,time_s\n";
    const std::pair<double, Eigen::Vector3d> rows[] = {
        {2.0, beside_pylon_2}, {3.0, in_the_sky}, {4.0, beside_pylon_1}};
    for (const auto& [time, enu] : rows) {
      const Geodetic g = frame.geodetic_from_enu(enu);
      geodetic << "t," << g.lat_deg << ',' << g.lon_deg << ',' << g.h_m << ',' << time << '\n';
    }
  }
  const auto score = run_cli({"score", "r", "--detections", "enu.csv", "--quiet"}, work.path());
  ASSERT_EQ(score.exit_status, 0) << score.err;
  const nlohmann::json json = read_json(work / "r/score.json");
  EXPECT_EQ(json.at("detections"), 3);
  EXPECT_EQ(json.at("false_alarms"), 1);
  EXPECT_EQ(json.at("interval"), "clopper-pearson");
  const nlohmann::json& pylon_2 = object_entry(json, "pylon-2");
  EXPECT_TRUE(pylon_2.at("detected").get<bool>());
  EXPECT_DOUBLE_EQ(pylon_2.at("first_detection_s").get<double>(), 2.0);
  EXPECT_TRUE(object_entry(json, "pylon-1").at("detected").get<bool>());
  EXPECT_FALSE(object_entry(json, "pylon-3").at("detected").get<bool>());
  // The warning time runs to the closest approach in truth.csv.
  const std::vector<ObjectTrack> tracks =
      read_truth_csv(work / "r/truth.csv", read_flight_facts(work / "r/summary.json"),
                     [](std::string_view id, std::string_view) { return id == "pylon-2"; });
  ASSERT_EQ(tracks.size(), 1u);
  const auto closest = std::min_element(
      tracks[0].rows.begin(), tracks[0].rows.end(),
      [](const TruthEntry& a, const TruthEntry& b) { return a.range_m < b.range_m; });
  EXPECT_NEAR(pylon_2.at("warning_time_s").get<double>(), closest->time_s - 2.0, 1e-9);
  const auto at_two = std::min_element(tracks[0].rows.begin(), tracks[0].rows.end(),
                                       [](const TruthEntry& a, const TruthEntry& b) {
                                         return std::abs(a.time_s - 2.0) < std::abs(b.time_s - 2.0);
                                       });
  EXPECT_NEAR(pylon_2.at("first_detection_range_m").get<double>(), at_two->range_m, 10.0);
  EXPECT_EQ(json.at("confusion").at("pole").at("pole"), 2);
  EXPECT_EQ(json.at("confusion").at("none").at("wire"), 1);
  const double hours = json.at("flight_hours").get<double>();
  EXPECT_NEAR(hours, 24 * 0.3330333327878778 / 3600.0, 1e-12);
  EXPECT_NEAR(json.at("false_alarms_per_hour").get<double>(), 1.0 / hours, 1e-6);
  const auto csv = csv_rows(work / "r/score.csv");
  ASSERT_EQ(csv.size(), 4u);
  EXPECT_EQ(csv[1][column(csv[0], "object")], "pylon-2");
  EXPECT_EQ(csv[1][column(csv[0], "distance_m")], "2.000");
  EXPECT_EQ(csv[2][column(csv[0], "object")], "");
  EXPECT_EQ(csv[3][column(csv[0], "object")], "pylon-1");
  EXPECT_EQ(csv[3][column(csv[0], "distance_m")], "2.000");

  // The same detections in WGS-84 match the same objects at the same distances.
  const auto geodetic =
      run_cli({"score", "r", "--detections", "wgs84.csv", "--out", "g", "--quiet"}, work.path());
  ASSERT_EQ(geodetic.exit_status, 0) << geodetic.err;
  const auto same = csv_rows(work / "g/score.csv");
  ASSERT_EQ(same.size(), 4u);
  for (std::size_t r = 1; r < 4; ++r) {
    EXPECT_EQ(same[r][column(same[0], "object")], csv[r][column(csv[0], "object")]);
    EXPECT_EQ(same[r][column(same[0], "distance_m")], csv[r][column(csv[0], "distance_m")]);
  }
  EXPECT_EQ(read_json(work / "g/score.json").at("false_alarms"), 1);
}

TEST(EvidenceCli, SweepDetectorAndScoreRunAsOneLoop) {
  const TempDir work("owsim_evidence_loop");
  fs::copy_file(kSource / "examples/pylon_line.yaml", work / "pylon_line.yaml");
  std::ofstream(work / "sweep.yaml") << "base: pylon_line.yaml\n"
                                     << "count: 3\nseed: 11\noutputs: csv,summary,truth\nvary:\n"
                                     << "  trajectory.waypoints.speed_mps: {uniform: [40, 60]}\n"
                                     << "  trajectory.duration_s: {values: [6]}\n"
                                     << "  seed: {member: true}\n";
  const auto sweep = run_cli({"sweep", "sweep.yaml", "--out", "campaign", "--quiet"}, work.path());
  ASSERT_EQ(sweep.exit_status, 0) << sweep.err;
  test::run_python_file(
      kSource / "examples/detectors/elevated_returns.py",
      {.arguments = (work / "campaign").string() + " " + (work / "detections").string()});
  for (const char* member : {"0", "1", "2"}) {
    EXPECT_TRUE(fs::exists(work / "detections" / (std::string(member) + ".csv"))) << member;
  }
  const auto score =
      run_cli({"score", "campaign", "--detections", "detections", "--quiet"}, work.path());
  ASSERT_EQ(score.exit_status, 0) << score.err;
  const nlohmann::json json = read_json(work / "campaign/score.json");
  EXPECT_EQ(json.at("flights"), 3);
  // The reference detector finds the pylons and some wires.
  EXPECT_GE(json.at("by_class").at("pole").at("detected").get<int>(), 3);
  EXPECT_GE(json.at("by_class").at("wire").at("detected").get<int>(), 3);
  std::size_t detections = 0;
  for (const char* member : {"0", "1", "2"}) {
    detections += csv_rows(work / "detections" / (std::string(member) + ".csv")).size() - 1;
  }
  EXPECT_EQ(json.at("detections").get<std::size_t>(), detections);
  EXPECT_EQ(csv_rows(work / "campaign/score.csv").size(), detections + 1);
  // Pd versus range has the class's objects in its nearest bin.
  const nlohmann::json& wires = json.at("by_class").at("wire");
  EXPECT_EQ(wires.at("pd_by_range").at(0).at("objects"), wires.at("objects"));
}

TEST(EvidenceCli, BadDetectionsAreRefusedInOneLineWithNothingWritten) {
  const TempDir work("owsim_evidence_score_errors");
  const auto run = run_cli({"run", (kSource / "examples/single_span.yaml").string(), "--out", "r",
                            "--duration", "2", "--outputs", "summary,truth", "--quiet"},
                           work.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const auto refused = [&](const std::string& text, const std::string& starts,
                           std::vector<std::string> extra = {}) {
    std::ofstream(work / "d.csv") << text;
    std::vector<std::string> arguments = {"score", "r", "--detections", "d.csv"};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const auto result = run_cli(arguments, work.path());
    EXPECT_NE(result.exit_status, 0) << text;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.err.rfind("owsim: " + starts, 0), 0u) << result.err;
    EXPECT_FALSE(fs::exists(work / "r/score.json")) << text;
  };
  refused("time_s,e_m,n_m\n1,2,3\n", "d.csv:1");
  refused("time_s,e_m,n_m,u_m\n1,2,3,4\n1,x,3,4\n", "d.csv:3: e_m");
  refused("time_s,e_m,n_m,u_m\n1,2,3,inf\n", "d.csv:2: u_m");
  refused("time_s,lat_deg,lon_deg,h_m\n1,91,3,4\n", "d.csv:2");
  refused("time_s,e_m,n_m,u_m\n1,2,3\n", "d.csv:2: u_m");
  refused("time_s,e_m,n_m,u_m\n", "--gate-m", {"--gate-m", "0"});
  // Regression (issue 45): the far side of the Earth and times of ±1e300 s were scored.
  refused("time_s,lat_deg,lon_deg,h_m\n1,-48.6881,-169.1553,0\n", "d.csv:2: lat_deg,lon_deg,h_m");
  refused("time_s,e_m,n_m,u_m\n1e300,0,0,0\n", "d.csv:2: time_s");
  refused("time_s,e_m,n_m,u_m\n1,0,0,0\n-1e300,0,0,0\n", "d.csv:3: time_s");
  // Regression (issue 45): a spreadsheet's byte-order mark was taken for part of "time_s".
  std::ofstream(work / "bom.csv") << "\xEF\xBB\xBFtime_s,e_m,n_m,u_m\n1,0,0,300\n";
  const auto bom = run_cli({"score", "r", "--detections", "bom.csv", "--quiet"}, work.path());
  ASSERT_EQ(bom.exit_status, 0) << bom.err;
  EXPECT_EQ(read_json(work / "r/score.json").at("detections"), 1);
  EXPECT_EQ(read_json(work / "r/score.json").at("false_alarms"), 1);
  // A folder for a run is where output `detections` wrote detections.csv: named when missing.
  fs::create_directories(work / "folder");
  const auto folder = run_cli({"score", "r", "--detections", "folder"}, work.path());
  EXPECT_EQ(folder.err, "owsim: folder/detections.csv: missing: no detections file\n");
}

}  // namespace
}  // namespace owsim
