// Protects the C ABI (capi/owsim/owsim.h, libowsim_c.so; INTERFACE.md "Embedding"), linked here
// against the shared library alone: for every bundled example and a HELLAS scenario the words and
// returns equal `owsim run`'s flight.d64 / flight.hellas bytes and points.csv rows frame for frame
// (rows formatted with printf, as a C program would); every bad input gives a status code and one
// line in this thread's last error, never a crash; a progress callback can stop a run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "embedding_reference.hpp"
#include "owsim/owsim.h"

namespace {

namespace fs = std::filesystem;
using owsim::test::TempDir;

const fs::path kExamples = fs::path(OWSIM_SOURCE_DIR) / "examples";
// OWSIM_CLASS_* by code.
const char* const kClassNames[] = {"wire", "pole", "tree", "ground", "building", "fog", "noise"};

// printf of a fixed-point cell, with points.csv's one spelling of zero ("0.0000", never "-0.0000").
std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string cell = text;
  if (cell[0] == '-' && cell.find_first_not_of("-0.") == std::string::npos) cell.erase(0, 1);
  return cell;
}

std::string csv_row(const owsim_return& r, const owsim_simulation* simulation) {
  char head[160];
  std::snprintf(head, sizeof head, "%lld,%d,%d,%d,%d,", static_cast<long long>(r.frame), r.pulse,
                r.line, r.fiber, r.return_number);
  char energy[32];
  std::snprintf(energy, sizeof energy, "%.9g", r.energy_rel);
  return std::string(head) + fixed(r.time_s, 9) + "," + fixed(r.range_m, 4) + "," +
         std::to_string(r.counter) + "," + fixed(r.e_m, 4) + "," + fixed(r.n_m, 4) + "," +
         fixed(r.u_m, 4) + "," + fixed(r.lat_deg, 9) + "," + fixed(r.lon_deg, 9) + "," +
         fixed(r.h_m, 4) + "," + kClassNames[r.surface] + "," +
         (r.object == OWSIM_NO_OBJECT ? "" : owsim_simulation_object_id(simulation, r.object)) +
         "," + energy + "," + (std::isnan(r.incidence_deg) ? "" : fixed(r.incidence_deg, 4));
}

TEST(CApi, EveryExampleAndHellasEqualsOwsimRunFrameForFrame) {
  const TempDir folder("owsim_c_api");
  for (const auto& [name, scenario] : owsim::test::reference_scenarios(folder.path())) {
    SCOPED_TRACE(name);
    const owsim::test::ReferenceRun reference = owsim::test::reference_run(scenario, folder / name);
    owsim_simulation_options options = owsim_simulation_options_default();
    options.frames = owsim::test::kReferenceFrames;
    owsim_simulation* simulation = nullptr;
    ASSERT_EQ(owsim_simulation_open_with(scenario.c_str(), &options, &simulation), OWSIM_OK)
        << owsim_last_error();
    EXPECT_EQ(owsim_simulation_frame_count(simulation), owsim::test::kReferenceFrames);
    EXPECT_EQ(static_cast<std::size_t>(owsim_simulation_word_size(simulation)),
              reference.word_size);
    owsim_frame* frame = nullptr;
    for (int64_t k = 0; k < owsim::test::kReferenceFrames; ++k) {
      ASSERT_EQ(owsim_simulate_frame(simulation, k, &frame), OWSIM_OK) << owsim_last_error();
      EXPECT_EQ(owsim_frame_index(frame), k);
      size_t bytes = 0;
      const void* words = owsim_frame_words(frame, &bytes);
      ASSERT_EQ(bytes, reference.frame_words[k].size());
      EXPECT_EQ(std::memcmp(words, reference.frame_words[k].data(), bytes), 0) << "frame " << k;
      size_t count = 0;
      const owsim_return* returns = owsim_frame_returns(frame, &count);
      const auto& rows = reference.frame_rows[static_cast<std::size_t>(k)];
      ASSERT_EQ(count, rows.size());
      for (size_t i = 0; i < count; ++i) {
        ASSERT_EQ(csv_row(returns[i], simulation), rows[i]) << "frame " << k;
      }
      size_t pulses = 0, rays = 0;
      const owsim_pulse* pulse = owsim_frame_pulses(frame, &pulses);
      const owsim_ray* ray = owsim_frame_rays(frame, &rays);
      ASSERT_EQ(pulses, owsim::test::kPulsesPerFrame);
      ASSERT_EQ(rays, owsim::test::kPulsesPerFrame);
      EXPECT_EQ(pulse[returns[0].pulse].fiber, returns[0].fiber);
      // A MilOWS pulse's encoder count and gates are its word's bits 47-32 (i16), 31 and 30
      // (SENSOR-SPEC §8), the negative counts included (§3: β = 0 → −21101).
      if (bytes == pulses * sizeof(uint64_t)) {
        const auto* word = static_cast<const uint64_t*>(words);
        for (size_t p = 0; p < pulses; ++p) {
          const auto count = static_cast<int16_t>(static_cast<uint16_t>(word[p] >> 32));
          ASSERT_EQ(static_cast<int64_t>(pulse[p].encoder), count) << p;
          ASSERT_EQ(pulse[p].frame_gate, (word[p] >> 31) & 1) << p;
          ASSERT_EQ(pulse[p].line_gate, (word[p] >> 30) & 1) << p;
        }
      }
      // The first return lies on its pulse's ray at its range.
      const owsim_ray& r = ray[returns[0].pulse];
      EXPECT_NEAR(r.origin_e_m + returns[0].range_m * r.dir_e, returns[0].e_m, 1e-9);
    }
    owsim_frame_release(frame);
    owsim_simulation_release(simulation);
  }
}

TEST(CApi, VersionMacrosAndRuntimeAgree) {
  EXPECT_EQ(owsim_version_number(), static_cast<uint32_t>(OWSIM_VERSION_NUMBER));
  EXPECT_STREQ(owsim_version(), OWSIM_VERSION_STRING);
}

TEST(CApi, NullHandlesAndBadArgumentsGiveStatusCodes) {
  owsim_frame* frame = nullptr;
  EXPECT_EQ(owsim_simulate_frame(nullptr, 0, &frame), OWSIM_ERROR_ARGUMENT);
  EXPECT_STREQ(owsim_last_error(), "owsim_simulate_frame: simulation is NULL");
  EXPECT_EQ(owsim_simulation_open(nullptr, nullptr), OWSIM_ERROR_ARGUMENT);
  EXPECT_EQ(owsim_simulation_frame_count(nullptr), -1);
  EXPECT_EQ(owsim_frame_words(nullptr, nullptr), nullptr);
  EXPECT_EQ(owsim_frame_index(nullptr), -1);
  EXPECT_EQ(owsim_simulation_run(nullptr, nullptr, nullptr), OWSIM_ERROR_ARGUMENT);
  owsim_simulation_release(nullptr);
  owsim_frame_release(nullptr);

  owsim_simulation* simulation = nullptr;
  owsim_simulation_options options = owsim_simulation_options_default();
  options.frames = 2;
  ASSERT_EQ(
      owsim_simulation_open_with((kExamples / "single_span.yaml").c_str(), &options, &simulation),
      OWSIM_OK);
  EXPECT_EQ(owsim_simulate_frame(simulation, 2, &frame), OWSIM_ERROR_ARGUMENT);
  EXPECT_STREQ(owsim_last_error(),
               "owsim_simulate_frame: frame 2 is out of range: the flight has frames 0..1");
  EXPECT_EQ(frame, nullptr);
  EXPECT_EQ(owsim_simulate_frame(simulation, -1, &frame), OWSIM_ERROR_ARGUMENT);
  EXPECT_EQ(owsim_simulate_frame(simulation, 0, nullptr), OWSIM_ERROR_ARGUMENT);
  EXPECT_EQ(owsim_simulation_object_id(simulation, 99), nullptr);
  EXPECT_EQ(owsim_simulation_object_id(simulation, OWSIM_NO_OBJECT), nullptr);  // a false return's
  options.struct_size = 4;
  owsim_simulation* other = nullptr;
  EXPECT_EQ(owsim_simulation_open_with("x.yaml", &options, &other), OWSIM_ERROR_ARGUMENT);
  EXPECT_NE(
      std::string(owsim_last_error())
          .find("struct_size is 4, expected " + std::to_string(sizeof(owsim_simulation_options)) +
                " (start from owsim_simulation_options_default())"),
      std::string::npos)
      << owsim_last_error();
  owsim_run_options run = owsim_run_options_default();
  run.struct_size = 4;
  EXPECT_EQ(owsim_simulation_run(simulation, &run, nullptr), OWSIM_ERROR_ARGUMENT);
  EXPECT_NE(std::string(owsim_last_error()).find("(start from owsim_run_options_default())"),
            std::string::npos);
  owsim_view_options view = owsim_view_options_default();
  view.struct_size = 4;
  EXPECT_EQ(owsim_view(".", &view, nullptr), OWSIM_ERROR_ARGUMENT);
  EXPECT_NE(std::string(owsim_last_error()).find("(start from owsim_view_options_default())"),
            std::string::npos);
  owsim_simulation_release(simulation);
}

TEST(CApi, BadScenariosAndFilesGiveOneLine) {
  owsim_simulation* simulation = nullptr;
  EXPECT_EQ(owsim_simulation_open("/nonexistent/scenario.yaml", &simulation), OWSIM_ERROR_FILE);
  EXPECT_STREQ(owsim_last_error(),
               "/nonexistent/scenario.yaml: cannot read the YAML file: no such file");
  EXPECT_EQ(simulation, nullptr);
  EXPECT_EQ(owsim_simulation_open_yaml("name: x\norigin: {lat: 95, lon: 0, h: 0}\n", "bad.yaml",
                                       nullptr, &simulation),
            OWSIM_ERROR_INPUT);
  const std::string message = owsim_last_error();
  EXPECT_TRUE(message.starts_with("bad.yaml:2: origin")) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_EQ(owsim_simulation_open_yaml("{[", nullptr, nullptr, &simulation), OWSIM_ERROR_INPUT);
  EXPECT_TRUE(std::string(owsim_last_error()).starts_with("scenario.yaml")) << owsim_last_error();
}

// Issue 33: a negative frame has no start (it was −0.33 s), and a host flying beyond the scenario's
// area is told the C option that widens it, which then works.
TEST(CApi, NegativeFramesAndTheFlightAreaOption) {
  owsim_simulation* simulation = nullptr;
  ASSERT_EQ(owsim_simulation_open((kExamples / "single_span.yaml").c_str(), &simulation), OWSIM_OK);
  EXPECT_TRUE(std::isnan(owsim_simulation_frame_start_s(simulation, -1)));
  EXPECT_STREQ(owsim_last_error(), "frame: must be ≥ 0, got -1");
  EXPECT_TRUE(std::isnan(owsim_simulation_frame_end_s(simulation, -1)));
  const double start = owsim_simulation_frame_start_s(simulation, 0);
  const double end = owsim_simulation_frame_end_s(simulation, 0);
  std::vector<owsim_pose> poses;  // level, east, 9 km from the scenario's span
  for (double t = start - 0.05; t < end + 0.05; t += 0.01) {
    poses.push_back({t, 9'000 + 40 * t, 0, 60, 0, 0, 90});
  }
  owsim_frame* frame = nullptr;
  EXPECT_EQ(owsim_simulate_frame_poses(simulation, 0, poses.data(), poses.size(), &frame),
            OWSIM_ERROR_INPUT);
  EXPECT_NE(std::string(owsim_last_error()).find("C owsim_simulation_options"), std::string::npos)
      << owsim_last_error();
  owsim_simulation_release(simulation);

  owsim_simulation_options options = owsim_simulation_options_default();
  const double area[4] = {8'000, -1'000, 10'000, 1'000};
  std::copy(std::begin(area), std::end(area), options.flight_area_enu_m);
  ASSERT_EQ(
      owsim_simulation_open_with((kExamples / "single_span.yaml").c_str(), &options, &simulation),
      OWSIM_OK);
  EXPECT_EQ(owsim_simulate_frame_poses(simulation, 0, poses.data(), poses.size(), &frame), OWSIM_OK)
      << owsim_last_error();
  owsim_frame_release(frame);
  owsim_simulation_release(simulation);
}

TEST(CApi, PosesThatDoNotCoverTheFrameAreRefused) {
  owsim_simulation* simulation = nullptr;
  ASSERT_EQ(owsim_simulation_open((kExamples / "single_span.yaml").c_str(), &simulation), OWSIM_OK);
  const double start = owsim_simulation_frame_start_s(simulation, 5);
  const double end = owsim_simulation_frame_end_s(simulation, 5);
  EXPECT_NEAR(end - start, 20'351 / 61'111.0, 1e-12);
  // A straight, level flight east at 40 m/s, 60 m up, sampled every 10 ms.
  std::vector<owsim_pose> poses;
  for (double t = start - 0.05; t < end - 0.1; t += 0.01) {
    poses.push_back({t, -600 + 40 * t, 0, 60, 0, 0, 90});
  }
  owsim_frame* frame = nullptr;
  EXPECT_EQ(owsim_simulate_frame_poses(simulation, 5, poses.data(), poses.size(), &frame),
            OWSIM_ERROR_INPUT);
  EXPECT_TRUE(std::string(owsim_last_error()).starts_with("poses: cover ")) << owsim_last_error();
  EXPECT_EQ(owsim_simulate_frame_poses(simulation, 5, nullptr, 3, &frame), OWSIM_ERROR_ARGUMENT);
  for (double t = poses.back().time_s + 0.01; t < end + 0.05; t += 0.01) {
    poses.push_back({t, -600 + 40 * t, 0, 60, 0, 0, 90});
  }
  ASSERT_EQ(owsim_simulate_frame_poses(simulation, 5, poses.data(), poses.size(), &frame), OWSIM_OK)
      << owsim_last_error();
  size_t count = 0;
  const owsim_return* returns = owsim_frame_returns(frame, &count);
  ASSERT_GT(count, 1000U);
  // Level flight 60 m up over flat ground at u = 0: the ground returns lie on it (noise along the
  // ray, σ = 0.42 m, moves them by less than 3 m up or down).
  for (size_t i = 0; i < count; ++i) {
    if (returns[i].surface == OWSIM_CLASS_GROUND) ASSERT_LT(std::abs(returns[i].u_m), 3.0);
  }
  owsim_frame_release(frame);
  owsim_simulation_release(simulation);
}

TEST(CApi, LastErrorIsPerThread) {
  EXPECT_EQ(owsim_simulation_open(nullptr, nullptr), OWSIM_ERROR_ARGUMENT);
  std::string other;
  std::thread([&] { other = owsim_last_error(); }).join();
  EXPECT_EQ(other, "");
  EXPECT_STRNE(owsim_last_error(), "");
}

int stop_after_two(int64_t frames_done, int64_t /*frames_total*/, void* user_data) {
  *static_cast<int64_t*>(user_data) = frames_done;
  return frames_done >= 2 ? 1 : 0;
}

TEST(CApi, RunWritesTheFilesAndTheCallbackCanStopIt) {
  const TempDir folder("owsim_c_run");
  owsim_simulation_options options = owsim_simulation_options_default();
  options.frames = 3;
  owsim_simulation* simulation = nullptr;
  ASSERT_EQ(
      owsim_simulation_open_with((kExamples / "single_span.yaml").c_str(), &options, &simulation),
      OWSIM_OK);
  owsim_run_options run = owsim_run_options_default();
  const std::string done_dir = (folder / "done").string();
  run.out_dir = done_dir.c_str();
  run.outputs = "d64,summary";
  owsim_run_report report{};
  ASSERT_EQ(owsim_simulation_run(simulation, &run, &report), OWSIM_OK) << owsim_last_error();
  EXPECT_EQ(report.frames, 3);
  EXPECT_EQ(report.pulses, 3U * 20'352U);
  EXPECT_EQ(fs::file_size(folder / "done" / "flight.d64"), 3U * 20'352U * 8U);

  const std::string stopped_dir = (folder / "stopped").string();
  run.out_dir = stopped_dir.c_str();
  int64_t seen = 0;
  run.progress = stop_after_two;
  run.user_data = &seen;
  EXPECT_EQ(owsim_simulation_run(simulation, &run, nullptr), OWSIM_ERROR_CANCELLED);
  EXPECT_EQ(seen, 2);
  EXPECT_FALSE(fs::exists(folder / "stopped" / "flight.d64"));
  run.outputs = "d64,bogus";
  EXPECT_EQ(owsim_simulation_run(simulation, &run, nullptr), OWSIM_ERROR_INPUT);
  owsim_simulation_release(simulation);
}

// owsim_view: the page of a run folder, its counts, and one clear error for a folder that is no
// owsim output.
TEST(CApi, ViewWritesThePageOfARunFolder) {
  const TempDir folder("owsim_c_view");
  owsim_simulation_options options = owsim_simulation_options_default();
  options.frames = 4;
  owsim_simulation* simulation = nullptr;
  const std::string scenario = (kExamples / "single_span.yaml").string();
  ASSERT_EQ(owsim_simulation_open_with(scenario.c_str(), &options, &simulation), OWSIM_OK);
  owsim_run_options run = owsim_run_options_default();
  const std::string out_dir = (folder / "run").string();
  run.out_dir = out_dir.c_str();
  run.outputs = "csv,summary,trajectory";
  ASSERT_EQ(owsim_simulation_run(simulation, &run, nullptr), OWSIM_OK) << owsim_last_error();
  owsim_simulation_release(simulation);

  owsim_view_options view = owsim_view_options_default();
  EXPECT_EQ(view.max_points, 2'000'000U);
  EXPECT_EQ(view.max_frames, 400);
  view.scenario_path = scenario.c_str();
  view.max_frames = 2;
  owsim_view_report report{};
  ASSERT_EQ(owsim_view(out_dir.c_str(), &view, &report), OWSIM_OK) << owsim_last_error();
  EXPECT_EQ(report.frames_total, 4);
  EXPECT_EQ(report.frames_shown, 2);
  EXPECT_GT(report.points_total, 0U);
  EXPECT_EQ(report.points_shown, report.points_total);
  EXPECT_EQ(fs::file_size(folder / "run" / "report.html"), report.bytes);

  fs::create_directories(folder / "empty");
  EXPECT_EQ(owsim_view((folder / "empty").c_str(), nullptr, nullptr), OWSIM_ERROR_INPUT);
  EXPECT_NE(std::string(owsim_last_error()).find("not an owsim output folder"), std::string::npos);
  EXPECT_EQ(owsim_view(nullptr, nullptr, nullptr), OWSIM_ERROR_ARGUMENT);
}

}  // namespace

// The detector through the C ABI: its warnings, printed as detections.csv rows, are the rows
// `owsim run --outputs detections` writes for the same frames.
namespace {

std::string warning_row(const owsim_warning& w) {
  static const char* const kObstacleClasses[] = {"none", "wire", "pole", "tree"};
  char head[96];
  std::snprintf(head, sizeof head, "%lld,", static_cast<long long>(w.frame));
  char middle[64];
  std::snprintf(middle, sizeof middle, ",%lld,%s,", static_cast<long long>(w.track),
                kObstacleClasses[w.obstacle_class]);
  return std::string(head) + fixed(w.time_s, 9) + middle + fixed(w.e_m, 3) + "," +
         fixed(w.n_m, 3) + "," + fixed(w.u_m, 3) + "," + fixed(w.range_m, 3) + "," +
         fixed(w.length_m, 3) + "," + fixed(w.width_m, 3) + "," + fixed(w.height_m, 3) + "," +
         std::to_string(w.points);
}

TEST(CApi, DetectorWarnsAsTheRunsDetectionsCsv) {
  const TempDir folder("owsim_c_api_detector");
  const fs::path approach = fs::path(OWSIM_SOURCE_DIR) / "tests/data/detector/approach.yaml";
  const owsim::test::CliResult run =
      owsim::test::run_cli({"run", approach.string(), "--frames", "40", "--outputs", "detections",
                            "--quiet", "--out", (folder / "run").string()},
                           fs::current_path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  std::istringstream written(owsim::test::read_whole_file(folder / "run/detections.csv"));
  std::string header;
  std::getline(written, header);
  std::vector<std::string> rows;
  for (std::string row; std::getline(written, row);) rows.push_back(row);
  ASSERT_GT(rows.size(), 20u);

  owsim_simulation_options options = owsim_simulation_options_default();
  options.frames = 40;
  owsim_simulation* simulation = nullptr;
  ASSERT_EQ(owsim_simulation_open_with(approach.c_str(), &options, &simulation), OWSIM_OK)
      << owsim_last_error();
  owsim_detector* detector = nullptr;
  ASSERT_EQ(owsim_detector_create(simulation, &detector), OWSIM_OK) << owsim_last_error();
  owsim_frame* frame = nullptr;
  std::vector<std::string> warned;
  for (int64_t k = 0; k < 40; ++k) {
    ASSERT_EQ(owsim_simulate_frame(simulation, k, &frame), OWSIM_OK) << owsim_last_error();
    const owsim_warning* warnings = nullptr;
    size_t count = 0;
    ASSERT_EQ(owsim_detector_add_frame(detector, frame, &warnings, &count), OWSIM_OK)
        << owsim_last_error();
    for (size_t w = 0; w < count; ++w) warned.push_back(warning_row(warnings[w]));
  }
  EXPECT_EQ(warned, rows);
  // A frame given twice, and NULL handles: a status and one line, no crash.
  const owsim_warning* warnings = nullptr;
  size_t count = 0;
  EXPECT_EQ(owsim_detector_add_frame(detector, frame, &warnings, &count), OWSIM_ERROR_INPUT);
  EXPECT_NE(std::string(owsim_last_error()).find("frame 39 given after frame 39"),
            std::string::npos)
      << owsim_last_error();
  EXPECT_EQ(owsim_detector_add_frame(nullptr, frame, &warnings, &count), OWSIM_ERROR_ARGUMENT);
  owsim_detector_release(detector);
  EXPECT_EQ(owsim_detector_create(nullptr, &detector), OWSIM_ERROR_ARGUMENT);
  EXPECT_EQ(detector, nullptr);
  owsim_frame_release(frame);
  owsim_simulation_release(simulation);
}

}  // namespace
