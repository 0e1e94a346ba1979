// Protects `owsim merge`: the per-pulse rule (a nearer synthetic return takes counter 1 and moves
// the recorded one to counter 2, a synthetic solid hides what lies behind it, nothing behind the
// recorded first return is written), and end to end — scenario A simulated, scenario B's objects
// merged into its recording, equals A + B simulated together word for word with noise off, for
// MilOWS and HELLAS, whole or cut mid-frame; only counter bits change, the frame structure stays;
// bad requests fail with one line and leave nothing behind.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "io/recording/recording_check.hpp"
#include "io/recording/recording_decoder.hpp"
#include "io/recording/recording_decoder_scene.hpp"
#include "io/recording/recording_merge.hpp"
#include "io/recording/word_file.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

using test::read_whole_file;
using test::run_cli;
using test::TempDir;

constexpr std::uint16_t kTimeout = 2066;

// Synthetic returns as select_returns gives them (counters only matter here).
PulseReturns synthetic(std::initializer_list<std::uint16_t> counters) {
  PulseReturns out;
  for (const std::uint16_t counter : counters) out.returns[out.count++].counter = counter;
  if (out.count >= 1) out.counter1 = out.returns[0].counter;
  if (out.count == 2) out.counter2 = out.returns[1].counter;
  return out;
}

const ReceiverParams kReceiver{};

TEST(MergePulseCounters, NearerSyntheticReturnTakesCounterOneAndMovesTheRecordedOne) {
  const MergedCounters merged =
      merge_pulse_counters(400, kTimeout, true, synthetic({300}), std::nullopt, kReceiver);
  EXPECT_TRUE(merged.changed);
  EXPECT_EQ(merged.counter1, 300);
  EXPECT_EQ(merged.counter2, 400);
  EXPECT_EQ(merged.synthetic_written, 1);
  EXPECT_EQ(merged.recorded_moved, 1);
}

TEST(MergePulseCounters, PulseWithoutRecordedReturnTakesTheSyntheticOnes) {
  const MergedCounters merged = merge_pulse_counters(
      kTimeout, kTimeout, true, synthetic({300, 301}), std::nullopt, kReceiver);
  // Both synthetic: the receiver has already separated them (true ranges ≥ 0.75 m apart).
  EXPECT_EQ(merged.counter1, 300);
  EXPECT_EQ(merged.counter2, 301);
  EXPECT_EQ(merged.synthetic_written, 2);
}

TEST(MergePulseCounters, SyntheticReturnBehindTheRecordedFirstReturnIsNotWritten) {
  const MergedCounters merged =
      merge_pulse_counters(400, 500, true, synthetic({450}), std::nullopt, kReceiver);
  EXPECT_FALSE(merged.changed);
  EXPECT_EQ(merged.counter1, 400);
  EXPECT_EQ(merged.counter2, 500);
  // Equal counts: not nearer.
  EXPECT_FALSE(
      merge_pulse_counters(400, 500, true, synthetic({400}), std::nullopt, kReceiver).changed);
}

TEST(MergePulseCounters, SyntheticSolidHidesTheRecordedReturnsBehindIt) {
  // A pole at count 300 in front of the recorded ground at 400: the ground is gone.
  const MergedCounters pole =
      merge_pulse_counters(400, kTimeout, true, synthetic({300}), std::uint16_t{300}, kReceiver);
  EXPECT_EQ(pole.counter1, 300);
  EXPECT_EQ(pole.counter2, kTimeout);
  EXPECT_EQ(pole.recorded_hidden, 1);
  EXPECT_EQ(pole.recorded_moved, 0);
  // Its echo below the threshold still blocks the ray.
  const MergedCounters dark =
      merge_pulse_counters(400, 500, true, synthetic({}), std::uint16_t{350}, kReceiver);
  EXPECT_TRUE(dark.changed);
  EXPECT_EQ(dark.counter1, kTimeout);
  EXPECT_EQ(dark.counter2, kTimeout);
  EXPECT_EQ(dark.recorded_hidden, 2);
  // A recorded wire in front of the solid stays, the ground behind it goes.
  const MergedCounters wire =
      merge_pulse_counters(200, 500, true, synthetic({}), std::uint16_t{350}, kReceiver);
  EXPECT_EQ(wire.counter1, 200);
  EXPECT_EQ(wire.counter2, kTimeout);
  // At the same count the solid does not hide: the counter cannot tell which is nearer.
  EXPECT_FALSE(
      merge_pulse_counters(400, kTimeout, true, synthetic({}), std::uint16_t{400}, kReceiver)
          .changed);
}

TEST(MergePulseCounters, MixedReturnsKeepTheReceiversSeparation) {
  // Synthetic 300, recorded 301 (0.6 m < 0.75 m): not a second return; recorded 340 is.
  const MergedCounters merged =
      merge_pulse_counters(301, 340, true, synthetic({300}), std::nullopt, kReceiver);
  EXPECT_EQ(merged.counter1, 300);
  EXPECT_EQ(merged.counter2, 340);
  EXPECT_EQ(merged.recorded_moved, 0);
  EXPECT_EQ(merged.recorded_dropped, 1);
  // Two nearer synthetic returns push both recorded ones out.
  const MergedCounters two =
      merge_pulse_counters(400, 500, true, synthetic({100, 200}), std::nullopt, kReceiver);
  EXPECT_EQ(two.counter1, 100);
  EXPECT_EQ(two.counter2, 200);
  EXPECT_EQ(two.recorded_dropped, 2);
}

TEST(MergePulseCounters, SingleCounterFormatTakesTheNearest) {
  // HELLAS: one counter; the second argument is not a field and stays as it is.
  const MergedCounters merged =
      merge_pulse_counters(400, 1234, false, synthetic({300, 350}), std::nullopt, kReceiver);
  EXPECT_EQ(merged.counter1, 300);
  EXPECT_EQ(merged.counter2, 1234);
  EXPECT_EQ(merged.synthetic_written, 1);
  EXPECT_EQ(merged.recorded_dropped, 1);
  EXPECT_FALSE(
      merge_pulse_counters(200, 0, false, synthetic({300}), std::nullopt, kReceiver).changed);
}

TEST(MergePulseCounters, OutcomeThatRestoresTheRecordingCountsNothing) {
  // The recorded ground at 401 lies behind the synthetic ground at 400 (noise); the synthetic
  // echo comes out at 401 too: the word stays as it was and nothing is counted.
  const MergedCounters merged =
      merge_pulse_counters(401, kTimeout, true, synthetic({401}), std::uint16_t{400}, kReceiver);
  EXPECT_FALSE(merged.changed);
  EXPECT_EQ(merged.counter1, 401);
  EXPECT_EQ(merged.counter2, kTimeout);
  EXPECT_EQ(merged.synthetic_written + merged.recorded_hidden + merged.recorded_dropped, 0);
}

std::filesystem::path data_dir() { return std::filesystem::path(OWSIM_SOURCE_DIR) / "tests/data"; }

// The three merge scenarios, as they are (MilOWS) or turned into HELLAS, in `dir`.
struct MergeScenarios {
  std::filesystem::path terrain, objects, both;
};

MergeScenarios scenarios(SensorModel model, const TempDir& dir) {
  MergeScenarios out{data_dir() / "merge_terrain.yaml", data_dir() / "merge_objects.yaml",
                     data_dir() / "merge_terrain_objects.yaml"};
  if (model == SensorModel::milows) return out;
  for (std::filesystem::path* path : {&out.terrain, &out.objects, &out.both}) {
    std::string text = read_whole_file(*path);
    const auto at = text.find("model: milows");
    EXPECT_NE(at, std::string::npos);
    text.replace(at, 13, "model: hellas");
    const auto copy = dir / path->filename();
    std::ofstream(copy) << text;
    *path = copy;
  }
  return out;
}

void simulate(const std::filesystem::path& scenario, const std::string& out, const TempDir& dir) {
  const auto run = run_cli({"run", scenario.string(), "--frames", "3", "--no-noise", "--outputs",
                            "d64", "--out", out, "--quiet", "--threads", "2"},
                           dir.path());
  ASSERT_EQ(run.exit_status, 0) << run.command << "\n" << run.err;
}

std::string words_file(SensorModel model) {
  return model == SensorModel::milows ? "flight.d64" : "flight.hellas";
}

// The same frame structure and no problem, as `owsim info` sees both files.
void expect_same_structure(const std::filesystem::path& merged,
                           const std::filesystem::path& original, SensorModel model) {
  ScanParams scan;
  scan.model = model;
  const RecordingReport a = check_recording(merged, scan);
  const RecordingReport b = check_recording(original, scan);
  EXPECT_TRUE(a.sound()) << render_text(a);
  EXPECT_EQ(a.words, b.words);
  EXPECT_EQ(a.pulses, b.pulses);
  EXPECT_EQ(a.complete_frames, b.complete_frames);
  EXPECT_EQ(a.lines, b.lines);
  EXPECT_EQ(a.leading_partial_pulses, b.leading_partial_pulses);
  EXPECT_EQ(a.trailing_partial_pulses, b.trailing_partial_pulses);
  EXPECT_EQ(a.problem_count, b.problem_count);
  EXPECT_EQ(a.time.first_tag, b.time.first_tag);
  EXPECT_EQ(a.time.last_tag, b.time.last_tag);
}

// Only the counter fields differ between the two files (MilOWS bits 27–16 and 11–0, HELLAS 11–0).
void expect_only_counters_differ(const std::string& merged, const std::string& original,
                                 SensorModel model) {
  ASSERT_EQ(merged.size(), original.size());
  const std::size_t word = model == SensorModel::milows ? 8 : 4;
  const std::uint64_t counters = model == SensorModel::milows ? 0x0FFF0FFFull : 0x0FFFull;
  std::size_t changed = 0;
  for (std::size_t at = 0; at < merged.size(); at += word) {
    std::uint64_t a = 0, b = 0;
    for (std::size_t i = 0; i < word; ++i) {
      a |= std::uint64_t{static_cast<unsigned char>(merged[at + i])} << (8 * i);
      b |= std::uint64_t{static_cast<unsigned char>(original[at + i])} << (8 * i);
    }
    ASSERT_EQ((a ^ b) & ~counters, 0u) << "word " << at / word;
    changed += a != b ? 1 : 0;
  }
  EXPECT_GT(changed, 100u);  // the objects are seen
}

class MergeEndToEnd : public ::testing::TestWithParam<SensorModel> {};

TEST_P(MergeEndToEnd, MergingObjectsEqualsSimulatingThemWithTheRecordedScene) {
  const SensorModel model = GetParam();
  const TempDir dir("owsim_merge");
  const MergeScenarios files = scenarios(model, dir);
  simulate(files.terrain, "a", dir);
  simulate(files.both, "ab", dir);
  const std::string name = words_file(model);
  const std::string merged_name =
      "merged/" + std::string(model == SensorModel::milows ? "m.d64" : "m.hellas");
  const auto merge = run_cli({"merge", "a/" + name, "--scenario", files.objects.string(),
                              "--no-noise", "--out", merged_name, "--threads", "2"},
                             dir.path());
  ASSERT_EQ(merge.exit_status, 0) << merge.command << "\n" << merge.err;
  EXPECT_NE(merge.err.find("sweep rebuilt in 3 frames"), std::string::npos) << merge.err;

  const std::string merged = read_whole_file(dir / merged_name);
  const std::string original = read_whole_file(dir / ("a/" + name));
  const std::string both = read_whole_file(dir / ("ab/" + name));
  ASSERT_NE(original, both)
      << "the objects must change the recording for this test to mean anything";
  EXPECT_TRUE(merged == both) << "merged ≠ A + B simulated";
  expect_only_counters_differ(merged, original, model);
  expect_same_structure(dir / merged_name, dir / ("a/" + name), model);
  const auto info = run_cli({"info", merged_name}, dir.path());
  EXPECT_EQ(info.exit_status, 0) << info.out;
}

INSTANTIATE_TEST_SUITE_P(Sensors, MergeEndToEnd,
                         ::testing::Values(SensorModel::milows, SensorModel::hellas),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// The library path, for the report's figures.
MergeReport merge_with(const std::filesystem::path& recording,
                       const std::filesystem::path& scenario, const std::filesystem::path& out,
                       const RecordingScenarioOverrides& overrides,
                       std::optional<double> start_hint = std::nullopt) {
  const Scenario parsed = load_recording_scenario(scenario, overrides);
  RecordingDecoder decoder(recording, parsed.scan, {start_hint});
  const RecordingScene scene(parsed, decoder.layout());
  MergeOptions options;
  options.out = out;
  return merge_recording(decoder, scene, parsed, options);
}

TEST(MergeLibrary, RecordingCutMidFrameMergesToTheSameSliceOfTheCombinedSimulation) {
  const TempDir dir("owsim_merge_cut");
  const MergeScenarios files = scenarios(SensorModel::milows, dir);
  simulate(files.terrain, "a", dir);
  simulate(files.both, "ab", dir);
  const std::string original = read_whole_file(dir / "a/flight.d64");
  const std::string both = read_whole_file(dir / "ab/flight.d64");
  // Words 9000 .. 3·20352 − 4321: mid-line at both ends, the first and last frames partial.
  const std::size_t begin = 9000 * 8, end = original.size() - 4321 * 8;
  std::ofstream(dir / "cut.d64", std::ios::binary) << original.substr(begin, end - begin);

  RecordingScenarioOverrides overrides;
  overrides.no_noise = true;
  const MergeReport report =
      merge_with(dir / "cut.d64", files.objects, dir / "cut_merged.d64", overrides);
  EXPECT_EQ(report.frames, 3u);
  EXPECT_EQ(report.frames_sweep_rebuilt, 3u);
  EXPECT_EQ(report.pulses, (end - begin) / 8);
  EXPECT_GT(report.words_changed, 100u);
  EXPECT_GT(report.recorded_moved, 0u);
  EXPECT_GT(report.recorded_hidden, 0u);
  EXPECT_EQ(report.time_tag_mismatches, 0u);
  EXPECT_TRUE(read_whole_file(dir / "cut_merged.d64") == both.substr(begin, end - begin));
}

TEST(MergeLibrary, WithoutTheSimulatorsSweepTheMeasuredBetaNearlyAlwaysAgrees) {
  // Another seed draws other frame jitters: the encoder words no longer match the rebuilt sweep,
  // so β is taken from the encoder (±0.0018°); only pulses grazing an object's edge may differ.
  const TempDir dir("owsim_merge_measured");
  const MergeScenarios files = scenarios(SensorModel::milows, dir);
  simulate(files.terrain, "a", dir);
  simulate(files.both, "ab", dir);
  RecordingScenarioOverrides overrides;
  overrides.no_noise = true;
  overrides.seed = 6;
  const MergeReport report =
      merge_with(dir / "a/flight.d64", files.objects, dir / "m.d64", overrides);
  EXPECT_EQ(report.frames_sweep_rebuilt, 0u);
  EXPECT_EQ(report.frames_sweep_measured, 3u);
  const std::string merged = read_whole_file(dir / "m.d64");
  const std::string both = read_whole_file(dir / "ab/flight.d64");
  ASSERT_EQ(merged.size(), both.size());
  std::size_t differ = 0, changed = 0;
  const std::string original = read_whole_file(dir / "a/flight.d64");
  for (std::size_t at = 0; at < merged.size(); at += 8) {
    differ += merged.compare(at, 8, both, at, 8) != 0 ? 1 : 0;
    changed += merged.compare(at, 8, original, at, 8) != 0 ? 1 : 0;
  }
  std::cout << differ << " of " << merged.size() / 8 << " words differ from A + B (" << changed
            << " changed by the merge)\n";
  EXPECT_GT(changed, 100u);
  EXPECT_LT(differ, changed / 20);
}

TEST(MergeCli, BadRequestsFailWithOneLineAndLeaveNothingBehind) {
  const TempDir dir("owsim_merge_cli");
  const MergeScenarios files = scenarios(SensorModel::milows, dir);
  simulate(files.terrain, "a", dir);
  const std::string before = read_whole_file(dir / "a/flight.d64");

  const auto onto_itself = run_cli(
      {"merge", "a/flight.d64", "--scenario", files.objects.string(), "--out", "a/../a/flight.d64"},
      dir.path());
  EXPECT_EQ(onto_itself.exit_status, 1);
  EXPECT_EQ(std::count(onto_itself.err.begin(), onto_itself.err.end(), '\n'), 1) << onto_itself.err;
  EXPECT_TRUE(read_whole_file(dir / "a/flight.d64") == before);

  std::ofstream(dir / "garbage.d64") << "twelve bytes";
  const auto garbage =
      run_cli({"merge", "garbage.d64", "--scenario", files.objects.string(), "--out", "out.d64"},
              dir.path());
  EXPECT_EQ(garbage.exit_status, 1) << garbage.err;
  EXPECT_NE(garbage.err.find("garbage.d64"), std::string::npos) << garbage.err;
  EXPECT_EQ(std::count(garbage.err.begin(), garbage.err.end(), '\n'), 1) << garbage.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.d64"));

  const auto format = run_cli({"merge", "a/flight.d64", "--format", "hellas", "--scenario",
                               files.objects.string(), "--out", "out.hellas"},
                              dir.path());
  EXPECT_EQ(format.exit_status, 1) << format.err;
  EXPECT_NE(format.err.find("sensor.model milows"), std::string::npos) << format.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.hellas"));
}

}  // namespace
}  // namespace owsim
