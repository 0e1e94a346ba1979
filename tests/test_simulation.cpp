// Protects the facade (owsim/simulation.hpp, INTERFACE.md "Embedding"): for every bundled example
// and a HELLAS scenario, Simulation::simulate_frame returns `owsim run`'s words and points.csv rows
// frame for frame; a scenario built in code equals the same scenario read from YAML and is checked
// with the loader's messages; co-simulation with pushed poses; bad input as one-line errors;
// concurrent calls give the sequential results; run() writes what `owsim run` writes.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "embedding_reference.hpp"
#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "owsim/owsim.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const fs::path kExamples = fs::path(OWSIM_SOURCE_DIR) / "examples";

// A return as its points.csv row.
std::string csv_row(const ReturnRecord& r, const std::vector<std::string>& ids) {
  std::string row;
  const auto integer = [&](std::int64_t value) {
    append_csv_integer(row, value);
    row += ',';
  };
  const auto fixed = [&](double value, int decimals) {
    append_csv_fixed(row, value, decimals);
    row += ',';
  };
  integer(r.frame);
  integer(r.pulse);
  integer(r.line);
  integer(r.fiber);
  integer(r.return_number);
  fixed(r.time_s, 9);
  fixed(r.range_m, 4);
  integer(r.counter);
  fixed(r.e_m, 4);
  fixed(r.n_m, 4);
  fixed(r.u_m, 4);
  fixed(r.lat_deg, 9);
  fixed(r.lon_deg, 9);
  fixed(r.h_m, 4);
  row += to_string(static_cast<SurfaceClass>(r.surface));
  row += ',';
  if (r.object != kNoObject) row += csv_cell(ids.at(r.object));  // a false return: empty
  row += ',';
  append_csv_significant(row, r.energy_rel, 9);
  row += ',';
  append_csv_fixed(row, r.incidence_deg, 4);
  return row;
}

std::string bytes_of(std::span<const std::byte> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

SimulationOptions frames(std::int64_t count) {
  SimulationOptions options;
  options.frames = count;
  return options;
}

TEST(Simulation, EveryExampleAndHellasEqualsOwsimRunFrameForFrame) {
  const TempDir folder("owsim_facade");
  for (const auto& [name, scenario] : test::reference_scenarios(folder.path())) {
    SCOPED_TRACE(name);
    const test::ReferenceRun reference = test::reference_run(scenario, folder / name);
    const Simulation simulation = Simulation::open(scenario, frames(test::kReferenceFrames));
    EXPECT_EQ(simulation.frame_count(), test::kReferenceFrames);
    Frame frame;  // one frame, refilled
    for (std::int64_t k = 0; k < test::kReferenceFrames; ++k) {
      simulation.simulate_frame(k, frame);
      ASSERT_EQ(frame.index(), k);
      EXPECT_EQ(frame.word_bytes().size(), test::kPulsesPerFrame * reference.word_size);
      EXPECT_TRUE(bytes_of(frame.word_bytes()) == reference.frame_words[k]) << "frame " << k;
      const auto& rows = reference.frame_rows[static_cast<std::size_t>(k)];
      ASSERT_EQ(frame.returns().size(), rows.size()) << "frame " << k;
      ASSERT_GT(rows.size(), 0U);
      for (std::size_t i = 0; i < rows.size(); ++i) {
        ASSERT_EQ(csv_row(frame.returns()[i], simulation.object_ids()), rows[i]) << "frame " << k;
      }
      EXPECT_EQ(frame.pulses().size(), test::kPulsesPerFrame);
      EXPECT_EQ(frame.rays().size(), test::kPulsesPerFrame);
    }
  }
}

// single_span.yaml, built in code.
Scenario single_span_in_code() {
  Scenario scenario;
  scenario.name = "single_span";
  scenario.seed = 42;
  scenario.origin = {48.6881, 10.8447, 450.0};
  scenario.mount.pitch_deg = -4;
  scenario.receiver.atmosphere = Atmosphere{};
  scenario.trajectory.speed_mps = 40;
  scenario.trajectory.waypoints_enu_m = {{-600, 0, 60}, {200, 0, 60}};
  scenario.trajectory.duration_s = 15;
  SpanSpec span;
  span.id = "line-a";
  span.from_en = {0, -200};
  span.to_en = {0, 200};
  span.support_height_1_m = span.support_height_2_m = 30;
  span.lowest_point_m = 20;
  span.conductor_diameter_m = 0.020;
  span.conductor_reflectivity = 0.4;
  span.support_poles = true;
  span.pole_diameter_m = 0.5;
  span.pole_reflectivity = 0.3;
  scenario.scene.spans.push_back(span);
  return scenario;
}

TEST(Simulation, ScenarioBuiltInCodeEqualsTheSameScenarioFromYaml) {
  const Simulation from_file = Simulation::open(kExamples / "single_span.yaml", frames(2));
  const Simulation in_code = Simulation::from_scenario(single_span_in_code(), frames(2));
  EXPECT_EQ(in_code.object_ids(), from_file.object_ids());
  for (std::int64_t k = 0; k < 2; ++k) {
    const Frame a = from_file.simulate_frame(k);
    const Frame b = in_code.simulate_frame(k);
    EXPECT_TRUE(bytes_of(a.word_bytes()) == bytes_of(b.word_bytes())) << "frame " << k;
    EXPECT_EQ(a.returns().size(), b.returns().size());
  }
}

TEST(Simulation, FromYamlTextEqualsTheFile) {
  const std::string text = test::read_whole_file(kExamples / "single_span.yaml");
  const Simulation from_text =
      Simulation::from_yaml(text, kExamples / "single_span.yaml", frames(1));
  const Simulation from_file = Simulation::open(kExamples / "single_span.yaml", frames(1));
  EXPECT_TRUE(bytes_of(from_text.simulate_frame(0).word_bytes()) ==
              bytes_of(from_file.simulate_frame(0).word_bytes()));
}

// The message of what `make` throws, or "" if nothing.
template <typename Make>
std::string error_of(Make&& make) {
  try {
    make();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

// A mistake made in code gets the loader's message for the same mistake in the file, after the
// name instead of "<file>:<line>".
TEST(Simulation, ScenarioBuiltInCodeIsCheckedWithTheLoadersMessages) {
  struct Mistake {
    const char* yaml_from;  // text in single_span.yaml
    const char* yaml_to;    // the mistake in YAML
    void (*in_code)(Scenario&);
  };
  const Mistake mistakes[] = {
      {"speed_mps: 40", "speed_mps: -5", [](Scenario& s) { s.trajectory.speed_mps = -5; }},
      {"      - {e: 200, n: 0, u: 60}\n", "",
       [](Scenario& s) { s.trajectory.waypoints_enu_m.pop_back(); }},
      {"reflectivity: 0.3}", "reflectivity: 1.5}",
       [](Scenario& s) { s.scene.spans[0].pole_reflectivity = 1.5; }},
      {"returns: first_second", "returns: first_second\n  threshold: 2",
       [](Scenario& s) { s.receiver.threshold = 2; }},
      {"    - id: line-a", "    - id: line/a", [](Scenario& s) { s.scene.spans[0].id = "line/a"; }},
  };
  const std::string text = test::read_whole_file(kExamples / "single_span.yaml");
  for (const Mistake& mistake : mistakes) {
    std::string yaml = text;
    yaml.replace(yaml.find(mistake.yaml_from), std::strlen(mistake.yaml_from), mistake.yaml_to);
    const std::string from_yaml = error_of([&] { (void)load_scenario_text(yaml, "s.yaml"); });
    Scenario scenario = single_span_in_code();
    mistake.in_code(scenario);
    const std::string in_code = error_of([&] { (void)Simulation::from_scenario(scenario); });
    SCOPED_TRACE(mistake.yaml_to);
    ASSERT_TRUE(from_yaml.starts_with("s.yaml:")) << from_yaml;
    ASSERT_TRUE(in_code.starts_with("single_span: ")) << in_code;
    // "s.yaml:<line>: <key>: <problem>" against "single_span: <key>: <problem>"
    const std::string yaml_tail = from_yaml.substr(from_yaml.find(": ") + 2);
    const std::string code_tail = in_code.substr(std::strlen("single_span: "));
    EXPECT_EQ(code_tail, yaml_tail);
    EXPECT_EQ(in_code.find('\n'), std::string::npos);
  }
}

// Poses sampled every 5 ms from the scenario's own trajectory, over [from, to].
std::vector<PoseSample> sampled_poses(const Simulation& simulation, double from_s, double to_s) {
  std::vector<PoseSample> poses;
  for (double t = from_s; t <= to_s + 1e-12; t += 0.005) {
    const Pose pose = simulation.setup().trajectory.pose_at(t);
    poses.push_back({t, pose.position_enu_m.x(), pose.position_enu_m.y(), pose.position_enu_m.z(),
                     pose.attitude.roll_deg, pose.attitude.pitch_deg, pose.attitude.heading_deg});
  }
  return poses;
}

TEST(Simulation, CoSimulationWithPushedPosesFollowsThem) {
  SimulationOptions options = frames(20);
  options.no_noise = true;
  const Simulation simulation = Simulation::open(kExamples / "pylon_line.yaml", options);
  for (const std::int64_t k : {3, 11}) {
    const std::vector<PoseSample> poses = sampled_poses(
        simulation, simulation.frame_start_s(k) - 0.05, simulation.frame_end_s(k) + 0.05);
    const Frame pushed = simulation.simulate_frame(k, poses);
    const Frame own = simulation.simulate_frame(k);
    ASSERT_EQ(pushed.milows_words().size(), own.milows_words().size());
    std::size_t same = 0;
    for (std::size_t i = 0; i < own.milows_words().size(); ++i) {
      same += pushed.milows_words()[i] == own.milows_words()[i] ? 1 : 0;
    }
    // Splines through 5 ms samples of the trajectory's own splines: µm apart, so a counter
    // differs only where a range sits on a rounding boundary.
    EXPECT_GE(static_cast<double>(same), 0.999 * static_cast<double>(own.milows_words().size()));
    for (std::size_t i = 0; i < own.rays().size(); ++i) {
      ASSERT_LT((pushed.rays()[i].origin_enu_m - own.rays()[i].origin_enu_m).norm(), 1e-4);
    }
  }
}

TEST(Simulation, CoSimulationRefusesPosesThatDoNotCoverTheFrame) {
  const Simulation simulation = Simulation::open(kExamples / "single_span.yaml", frames(10));
  const double start = simulation.frame_start_s(4);
  const double end = simulation.frame_end_s(4);
  const auto short_poses = sampled_poses(simulation, start, end - 0.1);
  EXPECT_TRUE(error_of([&] {
                (void)simulation.simulate_frame(4, short_poses);
              }).starts_with("poses: cover "));
  const std::vector<PoseSample> one = {sampled_poses(simulation, start, start)};
  EXPECT_TRUE(error_of([&] {
                (void)simulation.simulate_frame(4, one);
              }).starts_with("poses: need at least 2 samples"));
  auto backwards = sampled_poses(simulation, start - 0.1, end + 0.1);
  backwards[7].time_s = backwards[5].time_s;
  EXPECT_TRUE(
      error_of([&] { (void)simulation.simulate_frame(4, backwards); }).starts_with("poses[7]: "));
  auto far = sampled_poses(simulation, start - 0.1, end + 0.1);
  far[2].e_m = 1e6;
  EXPECT_TRUE(
      error_of([&] { (void)simulation.simulate_frame(4, far); }).starts_with("poses[2]: position"));
}

TEST(Simulation, BadInputIsOneLineError) {
  const Simulation simulation = Simulation::open(kExamples / "single_span.yaml", frames(3));
  EXPECT_EQ(error_of([&] { (void)simulation.simulate_frame(3); }),
            "frame: 3 is out of range: the flight has frames 0..2");
  EXPECT_EQ(error_of([&] { (void)simulation.simulate_frame(-1); }),
            "frame: -1 is out of range: the flight has frames 0..2");
  try {
    (void)Simulation::open("/nonexistent/scenario.yaml");
    FAIL() << "no error";
  } catch (const FileError& error) {
    EXPECT_EQ(std::string(error.what()),
              "/nonexistent/scenario.yaml: cannot read the YAML file: no such file");
  }
  EXPECT_EQ(
      error_of([] { (void)Simulation::from_yaml("name: [", "bad.yaml"); }).rfind("bad.yaml:", 0),
      0U);
  SimulationOptions both = frames(2);
  both.duration_s = 1.0;
  EXPECT_EQ(error_of([&] { (void)Simulation::open(kExamples / "single_span.yaml", both); }),
            "--frames: give --frames or --duration, not both");
}

TEST(Simulation, ConcurrentCallsGiveTheSequentialFrames) {
  SimulationOptions options = frames(6);
  options.threads = 2;
  const Simulation simulation = Simulation::open(kExamples / "corridor.yaml", options);
  std::vector<std::string> sequential;
  for (std::int64_t k = 0; k < 6; ++k) {
    sequential.push_back(bytes_of(simulation.simulate_frame(k).word_bytes()));
  }
  std::vector<std::string> concurrent(6);
  std::vector<std::thread> hosts;
  for (int h = 0; h < 3; ++h) {
    hosts.emplace_back([&, h] {
      Frame frame;
      for (std::int64_t k = h; k < 6; k += 3) {
        simulation.simulate_frame(k, frame);
        concurrent[static_cast<std::size_t>(k)] = bytes_of(frame.word_bytes());
      }
    });
  }
  for (std::thread& host : hosts) host.join();
  for (std::size_t k = 0; k < 6; ++k) EXPECT_TRUE(concurrent[k] == sequential[k]) << "frame " << k;
}

TEST(Simulation, RunWritesWhatOwsimRunWrites) {
  const TempDir folder("owsim_facade_run");
  const fs::path scenario = kExamples / "pylon_line.yaml";
  const test::CliResult cli =
      test::run_cli({"run", scenario.string(), "--frames", "4", "--outputs",
                     "d64,points,trajectory", "--quiet", "--out", (folder / "cli").string()},
                    fs::current_path());
  ASSERT_EQ(cli.exit_status, 0) << cli.err;

  const Simulation simulation = Simulation::open(scenario, frames(4));
  RunOptions run;
  run.out = folder / "facade";
  run.outputs = parse_output_list("d64,points,trajectory");
  std::vector<std::int64_t> progress;
  run.progress = [&](const RunProgress& at) {
    EXPECT_EQ(at.frames_total, 4);
    progress.push_back(at.frames_done);
  };
  const RunReport report = simulation.run(run);
  EXPECT_EQ(report.frames, 4);
  EXPECT_EQ(progress, (std::vector<std::int64_t>{1, 2, 3, 4}));
  for (const char* file :
       {"flight.d64", "points.csv", "points.las", "points.ply", "trajectory.csv"}) {
    EXPECT_TRUE(test::read_whole_file(folder / "facade" / file) ==
                test::read_whole_file(folder / "cli" / file))
        << file;
  }

  // A progress callback that throws stops the run and leaves nothing behind.
  run.out = folder / "stopped";
  run.progress = [](const RunProgress& at) {
    if (at.frames_done == 2) throw Error("stop");
  };
  EXPECT_EQ(error_of([&] { (void)simulation.run(run); }), "stop");
  EXPECT_FALSE(fs::exists(folder / "stopped" / "flight.d64"));
  EXPECT_FALSE(fs::exists(folder / "stopped" / "flight.d64.partial"));
}

}  // namespace
}  // namespace owsim
