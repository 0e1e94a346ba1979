// Protects pd.json's false returns (`owsim pd`, INTERFACE.md "Receiver noise and sunlight";
// evaluation/pd_report.hpp): for the flights it reads — a run folder, or every member of a sweep —
// `pulses` and `false_returns` are the sums of their summary.json's `pulses` and `returns.noise`
// (a summary without `returns.noise` counting 0) and `false_returns_per_s` is that count over the
// flights' frames × frame period; figures checked against counts written by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

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

}  // namespace
}  // namespace owsim
