// Protects pd.json's false returns (`owsim pd`, INTERFACE.md "Receiver noise and sunlight";
// evaluation/pd_report.hpp): for the flights it reads — a run folder, or every member of a sweep —
// `pulses` and `false_returns` are the sums of their summary.json's `pulses` and `returns.noise`
// (a summary without `returns.noise` counting 0) and `false_returns_per_s` is that count over the
// flights' frames × frame period; figures checked against counts written by hand. A run folder is
// data (issue 45): what no run writes — infinite, NaN or 1e308 ranges, negative frames, frames of
// ±9·10¹⁸ or past summary.json's count, a frame period of 1e-300 — is refused in one line naming
// the file, line and column (or key), with nothing written; three rows whose frames lie 10¹¹ apart
// take memory by the rows; --bins out of bounds is refused naming it; and a `pd` that cannot write
// its last file leaves the earlier ones as they were.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "evaluation/pd_report.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

constexpr double kFramePeriod = 1.0 / 3.0;
constexpr std::uint64_t kPulsesPerFrame = 20352;

// A run folder: summary.json with `frames` frames and, unless negative, `noise` false returns,
// and a truth.csv in which wire/1 is in view every frame at 600 m with one return.
void write_flight(const fs::path& folder, std::int64_t frames, std::int64_t noise) {
  fs::create_directories(folder);
  nlohmann::json summary = {{"frames", frames},
                            {"frame_period_s", kFramePeriod},
                            {"pulses", static_cast<std::uint64_t>(frames) * kPulsesPerFrame},
                            {"returns", {{"wire", frames}, {"ground", 1000}}},
                            {"objects", nlohmann::json::array()}};
  if (noise >= 0) summary["returns"]["noise"] = noise;
  std::ofstream(folder / "summary.json") << summary.dump(2);
  std::ofstream truth(folder / "truth.csv");
  truth << "frame,time_s,object,class,range_m,alpha_deg,beta_deg,in_view,returns,"
           "closing_speed_mps,time_to_reach_s\n";
  for (std::int64_t f = 0; f < frames; ++f) {
    truth << f << "," << f * kFramePeriod << ",wire/1,wire,600.0000,0.0,0.0,1,1,0.0,\n";
  }
}

nlohmann::json pd_json_of(const fs::path& folder, const fs::path& out) {
  PdOptions options;
  options.folder = folder;
  options.target_id = "wire/1";
  options.out = out;
  const PdReport report = write_pd_report(options);
  return nlohmann::json::parse(test::read_whole_file(out / "pd.json"));
}

TEST(PdReport, FalseReturnsAreTheFlightsSummedCountsOverTheirFlightTime) {
  const test::TempDir work("owsim_pd_false_returns");
  // A sweep of three members: 30 frames with 61 false returns, 15 frames with none written (a
  // summary from before the receiver had noise), 12 frames with 7.
  const fs::path sweep = work / "sweep";
  fs::create_directories(sweep);
  std::ofstream(sweep / "sweep.csv") << "member,seed,frames,pulses\n0,0,30,1\n1,1,15,1\n2,2,12,1\n";
  write_flight(sweep / "0", 30, 61);
  write_flight(sweep / "1", 15, -1);
  write_flight(sweep / "2", 12, 7);

  const nlohmann::json all = pd_json_of(sweep, work / "all");
  EXPECT_EQ(all["flights"], 3);
  EXPECT_EQ(all["pulses"], (30 + 15 + 12) * kPulsesPerFrame);
  EXPECT_EQ(all["false_returns"], 61 + 7);
  // 57 frames of 1/3 s: 19 s.
  EXPECT_NEAR(all["false_returns_per_s"].get<double>(), 68.0 / 19.0, 1e-12);

  // One run folder: its own figures.
  const nlohmann::json one = pd_json_of(sweep / "0", work / "one");
  EXPECT_EQ(one["flights"], 1);
  EXPECT_EQ(one["pulses"], 30 * kPulsesPerFrame);
  EXPECT_EQ(one["false_returns"], 61);
  EXPECT_NEAR(one["false_returns_per_s"].get<double>(), 6.1, 1e-12);

  // Without any: 0 per second.
  const nlohmann::json none = pd_json_of(sweep / "1", work / "none");
  EXPECT_EQ(none["false_returns"], 0);
  EXPECT_EQ(none["false_returns_per_s"].get<double>(), 0.0);
}

// Runs `owsim pd r --out o` in `work`: refused in one line starting with `starts`, writing
// nothing.
void expect_refused(const fs::path& work, std::vector<std::string> arguments,
                    const std::string& starts) {
  const auto result = test::run_cli(arguments, work);
  EXPECT_NE(result.exit_status, 0) << result.command;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("owsim: " + starts, 0), 0u) << result.err;
  EXPECT_FALSE(fs::exists(work / "o")) << result.command;
}

TEST(PdReport, WhatNoRunWritesIsRefusedNamingFileLineAndColumn) {
  const test::TempDir work("owsim_pd_hostile");
  const auto with_row = [&](const std::string& row) {
    write_flight(work / "r", 12, 3);
    std::ofstream(work / "r/truth.csv", std::ios::app) << row << "\n";
  };
  const std::vector<std::string> pd = {"pd", "r", "--out", "o"};
  // A wire in view at 600 m all flight, then at an infinite range: it once made the cumulative
  // Pd claim detection out to 1,300 m.
  with_row("11,3.8,wire/2,wire,inf,0,0,1,1,0,");
  expect_refused(work.path(), pd,
                 "r/truth.csv:14: range_m: must be a number in [0, 1000000] m, got 'inf'");
  with_row("11,3.8,wire/2,wire,nan,0,0,1,1,0,");
  expect_refused(work.path(), pd,
                 "r/truth.csv:14: range_m: must be a number in [0, 1000000] m, got 'nan'");
  with_row("11,3.8,wire/2,wire,1e308,0,0,1,1,0,");
  expect_refused(work.path(), pd, "r/truth.csv:14: range_m: must be a number in [0, 1000000] m");
  const std::string frame =
      "r/truth.csv:14: frame: must be a whole number in [0, 11] "
      "(summary.json counts 12 frames), got ";
  with_row("-1,3.8,wire/2,wire,600,0,0,1,1,0,");
  expect_refused(work.path(), pd, frame + "'-1'");
  with_row("12,3.8,wire/2,wire,600,0,0,1,1,0,");
  expect_refused(work.path(), pd, frame + "'12'");
  with_row("9000000000000000000,3.8,wire/2,wire,600,0,0,1,1,0,");
  expect_refused(work.path(), pd, frame + "'9000000000000000000'");
  with_row("-9000000000000000000,3.8,wire/2,wire,600,0,0,1,1,0,");
  expect_refused(work.path(), pd, frame + "'-9000000000000000000'");
  // An object not asked for is checked all the same.
  with_row("11,3.8,pole/1,pole,-5,0,0,1,1,0,");
  expect_refused(work.path(), {"pd", "r", "--target", "wire/1", "--out", "o"},
                 "r/truth.csv:14: range_m: must be a number in [0, 1000000] m, got '-5'");
  // summary.json's frame period, its frames and counts.
  write_flight(work / "r", 12, 3);
  const std::string summary = test::read_whole_file(work / "r/summary.json");
  const auto with_summary = [&](const std::string& from, const std::string& to) {
    std::string text = summary;
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
    std::ofstream(work / "r/summary.json") << text;
  };
  with_summary("\"frame_period_s\": 0.3333333333333333", "\"frame_period_s\": 1e-300");
  expect_refused(work.path(), pd,
                 "r/summary.json: frame_period_s: must be a number in [1e-06, 10000000] s, got "
                 "1e-300");
  with_summary("\"frames\": 12", "\"frames\": -12");
  expect_refused(work.path(), pd, "r/summary.json: frames: must be a whole number in [1, ");
  with_summary("\"noise\": 3", "\"noise\": -3");
  expect_refused(work.path(), pd, "r/summary.json: returns.noise: must be a whole number in [0, ");
  // Options: bins bounded.
  write_flight(work / "r", 12, 3);
  for (const char* bins : {"0:1300:1e308", "0:1e308:1", "0:1300:1e13", "0:1300:0.00001"}) {
    expect_refused(work.path(), {"pd", "r", "--bins", bins, "--out", "o"},
                   "--bins: expected LO:HI:STEP with 0 ≤ LO < HI ≤ 1000000 m, 0.001 m ≤ STEP ≤ "
                   "HI − LO and at most 100000 bins, got ");
  }
}

TEST(PdReport, RowsFarApartTakeMemoryByTheRowsNotTheirFrames) {
  const test::TempDir work("owsim_pd_sparse");
  // 10¹² frames of 1/3 s (a 3-frame window); three rows 4.5·10¹¹ frames apart. A vector by frame
  // would take 7 TB (a 3-row file whose frames reach 4·10⁸ took 3.1 GB).
  write_flight(work / "r", 1, 0);
  std::string summary = test::read_whole_file(work / "r/summary.json");
  const std::string one_frame = "\"frames\": 1,";
  ASSERT_NE(summary.find(one_frame), std::string::npos) << summary;
  summary.replace(summary.find(one_frame), one_frame.size(), "\"frames\": 1000000000000,");
  std::ofstream(work / "r/summary.json") << summary;
  std::ofstream(work / "r/truth.csv")
      << "frame,time_s,object,class,range_m,alpha_deg,beta_deg,in_view,returns,"
         "closing_speed_mps,time_to_reach_s\n"
      << "0,0.1,wire/1,wire,600,0,0,1,1,0,\n"
      << "450000000000,150000000000.1,wire/1,wire,600,0,0,1,0,0,\n"
      << "900000000000,300000000000.1,wire/1,wire,600,0,0,1,2,0,\n";
  const nlohmann::json json = pd_json_of(work / "r", work / "o");
  EXPECT_EQ(json["windows"], 3);
  EXPECT_EQ(json["windows_detected"], 2);
  EXPECT_EQ(json["trials"], 1);
  EXPECT_EQ(json["trials_detected"], 1);
}

TEST(PdReport, AFailedPdReplacesNoneOfItsFiles) {
  const test::TempDir work("owsim_pd_all_or_none");
  write_flight(work / "r", 30, 5);
  const auto first = test::run_cli({"pd", "r", "--out", "o", "--quiet"}, work.path());
  ASSERT_EQ(first.exit_status, 0) << first.err;
  const std::string csv = test::read_whole_file(work / "o/pd.csv");
  const std::string json = test::read_whole_file(work / "o/pd.json");
  ASSERT_FALSE(csv.empty());
  // The last file cannot be written — a folder at its name, or at its temporary's: the files
  // before it keep their bytes, though this run's would differ (other bins).
  for (const char* blocked : {"o/pd.svg", "o/pd.svg.partial"}) {
    fs::remove_all(work / "o/pd.svg");
    fs::create_directories(work / blocked / "inside");
    const auto failed =
        test::run_cli({"pd", "r", "--out", "o", "--bins", "0:1300:100"}, work.path());
    EXPECT_NE(failed.exit_status, 0) << blocked;
    EXPECT_EQ(std::count(failed.err.begin(), failed.err.end(), '\n'), 1) << failed.err;
    EXPECT_EQ(failed.err.rfind("owsim: o/pd.svg", 0), 0u) << failed.err;
    EXPECT_EQ(test::read_whole_file(work / "o/pd.csv"), csv) << blocked;
    EXPECT_EQ(test::read_whole_file(work / "o/pd.json"), json) << blocked;
    EXPECT_FALSE(fs::exists(work / "o/pd.csv.partial")) << blocked;
    EXPECT_FALSE(fs::exists(work / "o/pd.json.partial")) << blocked;
    fs::remove_all(work / blocked);
  }
  const auto after =
      test::run_cli({"pd", "r", "--out", "o", "--bins", "0:1300:100", "--quiet"}, work.path());
  ASSERT_EQ(after.exit_status, 0) << after.err;
  EXPECT_NE(test::read_whole_file(work / "o/pd.csv"), csv);
  EXPECT_TRUE(fs::is_regular_file(work / "o/pd.svg"));
}

}  // namespace
}  // namespace owsim
