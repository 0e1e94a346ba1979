// Protects the detection evidence end to end (INTERFACE.md "Ground truth and detection evidence"):
// truth.csv counts every return points.csv holds on each object; a run folder's scenario.yaml
// flies the same bytes again; truth.csv alone equals the full run's; `owsim pd` over a sweep
// agrees with an independent recount (tests/oracles/pd_oracle.py: numpy counts, scipy's beta
// quantiles to 1e-9); physics: with no noise a head-on 5 mm wire is never detected beyond
// max_detection_range_m and always within it once the wire spans HELLAS's whole scan line; bad
// criteria and folders are refused in one line with nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "cli_runner.hpp"
#include "evaluation/truth_table.hpp"
#include "owsim/simulation.hpp"
#include "python_oracle.hpp"
#include "sensor/receiver.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::TempDir;

const fs::path kSource = OWSIM_SOURCE_DIR;

std::vector<std::vector<std::string>> csv_rows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream split(line);
    std::string cell;
    while (std::getline(split, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto found = std::find(header.begin(), header.end(), name);
  EXPECT_NE(found, header.end()) << name;
  return static_cast<std::size_t>(found - header.begin());
}

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
  std::ofstream(work / "sweep.yaml")
      << "base: " << (kSource / "examples/campaigns/hellas_5mm_approach.yaml").string() << "\n"
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
  ASSERT_NEAR(max_range, 483.8, 0.1);  // README "What the default sensor detects"
  // The wire spans HELLAS's whole line (α ±21°) nearer than 1,000 m / tan 21° from its middle.
  const std::vector<ObjectTrack> tracks =
      read_truth_csv(work / "head_on/truth.csv",
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

}  // namespace
}  // namespace owsim
