// Protects `owsim bench` (INTERFACE.md `owsim bench --json`): every field is there with its type,
// the counts match the frames asked for, every rate is positive and the derived figures agree
// with the rates they come from; the word file goes to a temporary folder that is removed; bad
// input is one stderr line and a non-zero exit. No timing is asserted.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::TempDir;

const std::string kSingleSpan = std::string(OWSIM_SOURCE_DIR) + "/examples/single_span.yaml";
constexpr int kPulsesPerFrame = 128 * 159;  // SENSOR-SPEC §2

// Runs `owsim bench` with TMPDIR pointing into `scratch`, so the test sees what it leaves there.
test::CliResult run_bench(const std::vector<std::string>& arguments, const TempDir& work,
                          const fs::path& scratch) {
  fs::create_directories(scratch);
  const char* previous = std::getenv("TMPDIR");
  const std::string saved = previous != nullptr ? previous : "";
  ::setenv("TMPDIR", scratch.c_str(), 1);
  std::vector<std::string> full = {"bench"};
  full.insert(full.end(), arguments.begin(), arguments.end());
  test::CliResult result = run_cli(full, work.path());
  if (previous != nullptr) {
    ::setenv("TMPDIR", saved.c_str(), 1);
  } else {
    ::unsetenv("TMPDIR");
  }
  return result;
}

TEST(CliBench, JsonHoldsEveryFieldConsistently) {
  const TempDir work("owsim_test_bench");
  const fs::path scratch = work / "tmp";
  const auto run = run_bench({kSingleSpan, "--frames", "2", "--threads", "2", "--repeats", "1",
                              "--brute-force-pulses", "300", "--json"},
                             work, scratch);
  ASSERT_EQ(run.exit_status, 0) << run.command << "\n" << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);

  ASSERT_TRUE(report.at("scenario").is_string());
  EXPECT_EQ(report.at("scenario"), "single_span");
  ASSERT_TRUE(report.at("frames").is_number_integer());
  EXPECT_EQ(report.at("frames"), 2);
  ASSERT_TRUE(report.at("pulses").is_number_integer());
  EXPECT_EQ(report.at("pulses"), 2 * kPulsesPerFrame);
  ASSERT_TRUE(report.at("threads").is_number_integer());
  EXPECT_EQ(report.at("threads"), 2);

  for (const char* key :
       {"end_to_end_pulses_per_s", "trace_only_pulses_per_s", "brute_force_pulses_per_s",
        "single_thread_pulses_per_s", "las_pulses_per_s", "points_pulses_per_s",
        "truth_pulses_per_s", "realtime_factor", "peak_rss_mb", "traversal_only_pulses_per_s",
        "traversal_share_paired", "end_to_end_over_trace_paired",
        "traversal_share_single_thread_paired", "end_to_end_over_trace_single_thread_paired",
        "detections_pulses_per_s", "detections_ratio_paired", "detector_frames_per_s",
        "detector_realtime_factor"}) {
    ASSERT_TRUE(report.at(key).is_number()) << key;
    const double value = report.at(key).get<double>();
    EXPECT_TRUE(std::isfinite(value) && value > 0.0) << key << " = " << value;
  }
  // The paired ratio is a median of per-round ratios of timings: a positive number (no bound on
  // it: two tiny runs under a loaded test machine can differ several-fold).
  ASSERT_TRUE(report.at("truth_ratio_paired").is_number());
  const double paired = report.at("truth_ratio_paired").get<double>();
  EXPECT_TRUE(std::isfinite(paired) && paired > 0.0) << paired;
  // The real-time factor is end-to-end against the sensor's 61,111 pulses/s.
  EXPECT_NEAR(report.at("realtime_factor").get<double>(),
              report.at("end_to_end_pulses_per_s").get<double>() / 61'111.0,
              1e-9 * report.at("realtime_factor").get<double>());

  // The detector's real-time factor is its frames per second times a frame's duration.
  EXPECT_NEAR(report.at("detector_realtime_factor").get<double>(),
              report.at("detector_frames_per_s").get<double>() * kPulsesPerFrame / 61'111.0,
              1e-9 * report.at("detector_realtime_factor").get<double>());

  // The winning query form is one of the four, and it is the fastest of them.
  ASSERT_TRUE(report.at("trace_api").is_string());
  const std::string api = report.at("trace_api");
  const nlohmann::json& by_api = report.at("trace_api_pulses_per_s");
  ASSERT_TRUE(by_api.contains(api)) << api;
  for (const char* form : {"per_ray", "stream", "packet8", "packet16"}) {
    ASSERT_TRUE(by_api.at(form).is_number()) << form;
    EXPECT_GT(by_api.at(form).get<double>(), 0.0) << form;
    EXPECT_LE(by_api.at(form).get<double>(), by_api.at(api).get<double>()) << form;
  }
  EXPECT_DOUBLE_EQ(by_api.at(api).get<double>(),
                   report.at("trace_only_pulses_per_s").get<double>());

  // The brute-force subset is about the size asked for, never more than the active pulses.
  const auto subset = report.at("brute_force_subset_pulses").get<std::int64_t>();
  EXPECT_GE(subset, 300);
  EXPECT_LE(subset, 2 * 127 * 159);
  EXPECT_EQ(report.at("repeats"), 1);

  // The word file went to a temporary folder that is gone; nothing was written in the work dir.
  EXPECT_TRUE(fs::is_empty(scratch)) << fs::begin(fs::directory_iterator(scratch))->path();
  EXPECT_FALSE(fs::exists(work / "out"));
}

TEST(CliBench, TextReportNamesEveryFigure) {
  const TempDir work("owsim_test_bench");
  const auto run =
      run_bench({kSingleSpan, "--frames", "1", "--repeats", "1", "--brute-force-pulses", "100"},
                work, work / "tmp");
  ASSERT_EQ(run.exit_status, 0) << run.command << "\n" << run.err;
  for (const char* figure : {"single_span: 1 frames, 20352 pulses", "end-to-end", "trace-only",
                             "single thread", "brute force", "peak memory", "real time"}) {
    EXPECT_NE(run.out.find(figure), std::string::npos) << figure << " missing from\n" << run.out;
  }
}

TEST(CliBench, MoreFramesThanTheTrajectoryHoldsIsOneErrorLine) {
  const TempDir work("owsim_test_bench");
  const auto run = run_bench({kSingleSpan, "--frames", "100000", "--json"}, work, work / "tmp");
  EXPECT_NE(run.exit_status, 0);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_NE(run.err.find("single_span.yaml"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("frames"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
}

TEST(CliBench, MissingScenarioOrBadFramesIsRefused) {
  const TempDir work("owsim_test_bench");
  const auto missing = run_bench({"no_such_scenario.yaml", "--json"}, work, work / "tmp");
  EXPECT_NE(missing.exit_status, 0);
  EXPECT_NE(missing.err.find("no_such_scenario.yaml"), std::string::npos) << missing.err;
  const auto zero = run_bench({kSingleSpan, "--frames", "0"}, work, work / "tmp");
  EXPECT_NE(zero.exit_status, 0);
  EXPECT_NE(zero.err.find("--frames"), std::string::npos) << zero.err;
}

}  // namespace
}  // namespace owsim
