// The distributed driver with one process (distributed/distributed_run.hpp, sweep_run.hpp): the
// placement path — bytes written at scanned offsets, frames' facts replayed at process 0 — gives
// every output of Simulation::run byte for byte, resumes a checkpoint of a one-process run, and
// a one-process sweep writes every member and sweep.csv. Runs without MPI and under the
// sanitizers; tests/mpi_run.sh and mpi_sweep.sh check 1, 2 and 3 processes through mpirun.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "distributed/distributed_run.hpp"
#include "distributed/sweep_run.hpp"
#include "io/run/run_checkpoint.hpp"
#include "tests/cli_runner.hpp"
#include "tests/synthetic_flight.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

const fs::path kCorridor = fs::path(OWSIM_SOURCE_DIR) / "examples" / "corridor.yaml";

nlohmann::json summary_without_run_facts(const fs::path& folder) {
  nlohmann::json summary = nlohmann::json::parse(test::read_whole_file(folder / "summary.json"));
  for (const char* fact :
       {"setup_s", "wall_s", "pulses_per_s", "realtime_factor", "threads", "processes"}) {
    EXPECT_TRUE(summary.contains(fact)) << fact;
    summary.erase(fact);
  }
  return summary;
}

void expect_same_outputs(const fs::path& a, const fs::path& b) {
  const std::map<std::string, std::string> files = test::files_under(a);
  const std::map<std::string, std::string> others = test::files_under(b);
  ASSERT_EQ(files.size(), others.size());
  EXPECT_GE(files.size(), 8u);
  for (const auto& [file, bytes] : files) {
    ASSERT_TRUE(others.contains(file)) << file;
    if (file == "summary.json") continue;
    EXPECT_TRUE(bytes == others.at(file)) << file << " differs";
  }
  EXPECT_EQ(summary_without_run_facts(a), summary_without_run_facts(b));
}

Simulation corridor(std::int64_t frames) {
  SimulationOptions options;
  options.frames = frames;
  options.threads = 2;
  return Simulation::open(kCorridor, options);
}

TEST(DistributedRun, OneProcessWritesTheBytesOfARun) {
  test::TempDir work;
  const Simulation simulation = corridor(21);
  RunOptions run;
  run.out = work.path() / "run";
  static_cast<void>(simulation.run(run));
  std::unique_ptr<Communicator> comm = single_process_communicator();
  RunOptions placed = run;
  placed.out = work.path() / "placed";
  DistributedRunOptions blocks;
  blocks.frames_per_block = 4;  // five full blocks and one of a frame
  const RunReport report = run_distributed(*comm, simulation, placed, blocks);
  EXPECT_EQ(report.frames, 21);
  EXPECT_EQ(report.processes, 1);
  expect_same_outputs(work.path() / "run", work.path() / "placed");
}

// Regression (issue 47): a distributed run refused mcap. Process 0 now appends the chunks the
// processes built, in frame order: flight.mcap and metadata.yaml are a one-process run's bytes.
TEST(DistributedRun, OneProcessPlacesTheChunksOfFlightMcap) {
  test::TempDir work;
  const Simulation simulation = corridor(11);
  RunOptions run;
  run.out = work.path() / "run";
  run.outputs = parse_output_list("mcap,d64");
  static_cast<void>(simulation.run(run));
  std::unique_ptr<Communicator> comm = single_process_communicator();
  RunOptions placed = run;
  placed.out = work.path() / "placed";
  DistributedRunOptions blocks;
  blocks.frames_per_block = 4;  // two full blocks and one of three frames
  static_cast<void>(run_distributed(*comm, simulation, placed, blocks));
  const std::map<std::string, std::string> files = test::files_under(work.path() / "run");
  EXPECT_EQ(files.size(), 4u);  // flight.d64, flight.mcap, metadata.yaml, scenario.yaml
  EXPECT_EQ(files, test::files_under(work.path() / "placed"));
  EXPECT_GT(files.at("flight.mcap").size(), 11u * 1000u);
  EXPECT_NE(files.at("metadata.yaml").find("message_count: 35\n"), std::string::npos)
      << files.at("metadata.yaml");  // 3 a frame and the 2 latched ones
}

TEST(DistributedRun, RefusesToResumeFlightMcapInOneLineBeforeWritingAnything) {
  test::TempDir work;
  const Simulation simulation = corridor(2);
  std::unique_ptr<Communicator> comm = single_process_communicator();
  RunOptions run;
  run.out = work.path() / "run";
  run.outputs = parse_output_list("d64,mcap");
  run.resume = true;
  try {
    static_cast<void>(run_distributed(*comm, simulation, run));
    FAIL() << "no error";
  } catch (const JobError& error) {
    EXPECT_STREQ(error.what(),
                 "--resume: flight.mcap (output mcap) cannot be continued from a checkpoint; run "
                 "without --resume, or without mcap");
  }
  EXPECT_FALSE(std::filesystem::exists(work.path() / "run"));
}

TEST(DistributedRun, ResumesTheCheckpointOfAOneProcessRun) {
  test::TempDir work;
  const Simulation simulation = corridor(30);
  RunOptions run;
  run.out = work.path() / "run";
  static_cast<void>(simulation.run(run));

  // A run stopped after frame 11 by its progress callback leaves its temporaries and checkpoint
  // only if one was written: write one at every frame.
  RunOptions stopped;
  stopped.out = work.path() / "resumed";
  FlightOutputOptions output_options =
      run_output_options(simulation.setup(), simulation.run_fingerprint(stopped), stopped);
  output_options.checkpoint_interval_s = 0;
  {
    FlightOutputs outputs(output_options, simulation.setup().scene,
                          simulation.setup().scenario.scan, simulation.setup().local_frame);
    simulation.in_arena([&] {
      simulate_frames(simulation.setup().simulator, simulation.setup(), FlightRange{0, 12}, 2,
                      outputs);
    });
    // Keep what a killed process keeps: the temporaries and the checkpoint (no destructor ran).
    for (const auto& entry : fs::directory_iterator(stopped.out.value())) {
      if (entry.path().extension() == ".partial" || entry.path().filename().string()[0] == '.') {
        fs::copy(entry.path(), work.path() / entry.path().filename());
      }
    }
  }
  for (const auto& entry : fs::directory_iterator(work.path())) {
    if (entry.is_regular_file()) {
      fs::rename(entry.path(), stopped.out.value() / entry.path().filename());
    }
  }
  ASSERT_TRUE(read_run_checkpoint(run_checkpoint_path(stopped.out.value())));

  std::unique_ptr<Communicator> comm = single_process_communicator();
  stopped.resume = true;
  std::string notice;
  stopped.notice = [&](std::string_view note) { notice = note; };
  const RunReport report = run_distributed(*comm, simulation, stopped);
  EXPECT_EQ(report.first_frame, 12) << notice;
  expect_same_outputs(work.path() / "run", work.path() / "resumed");
}

TEST(DistributedSweep, OneProcessRunsEveryMemberAndWritesTheTable) {
  test::TempDir work;
  const fs::path sweep_file = work.path() / "sweep.yaml";
  fs::copy_file(kCorridor, work.path() / "corridor.yaml");  // a sweep reads only its own tree
  std::ofstream(sweep_file) << "base: corridor.yaml\n"
                            << "count: 3\nseed: 5\noutputs: d64\n"
                            << "vary:\n  trajectory.duration_s: {values: [2, 4, 3]}\n"
                            << "  seed: {member: true}\n";
  const SweepSpec spec = read_sweep_file(sweep_file);
  std::unique_ptr<Communicator> comm = single_process_communicator();
  SweepRunOptions options;
  options.out = work.path() / "out";
  options.threads = 2;
  const SweepReport report = run_sweep(*comm, spec, options);
  EXPECT_EQ(report.ran, 3);
  EXPECT_EQ(report.skipped, 0);
  const std::string table = test::read_whole_file(options.out / "sweep.csv");
  std::istringstream lines(table);
  std::string header;
  std::getline(lines, header);
  EXPECT_TRUE(header.starts_with("member,trajectory.duration_s,seed,frames,pulses,returns_wire"))
      << header;
  for (int m = 0; m < 3; ++m) {
    // Each member is the run of its own scenario: its summary says its frames and seed.
    const nlohmann::json summary = nlohmann::json::parse(
        test::read_whole_file(options.out / std::to_string(m) / "summary.json"));
    EXPECT_EQ(summary["seed"], m);
    std::string row;
    std::getline(lines, row);
    const int frames = summary["frames"].get<int>();
    EXPECT_TRUE(row.starts_with(std::to_string(m) + "," +
                                std::vector<std::string>{"2", "4", "3"}[m] + "," +
                                std::to_string(m) + "," + std::to_string(frames) + ","))
        << row;
    EXPECT_TRUE(fs::exists(options.out / std::to_string(m) / "flight.d64"));
  }

  // Resumed: complete members are skipped, a missing one is run again to the same bytes.
  const std::string words = test::read_whole_file(options.out / "1" / "flight.d64");
  fs::remove(options.out / "1" / "summary.json");
  fs::remove(options.out / "1" / "flight.d64");
  options.resume = true;
  const SweepReport resumed = run_sweep(*comm, spec, options);
  EXPECT_EQ(resumed.ran, 1);
  EXPECT_EQ(resumed.skipped, 2);
  EXPECT_TRUE(test::read_whole_file(options.out / "1" / "flight.d64") == words);
  EXPECT_EQ(test::read_whole_file(options.out / "sweep.csv"), table);
}

// Regression (issue 45): members were checked only as each one ran, so with `values: [40, fast]`
// member 0 flew (and .owsim-sweep.json was written) before member 1 was refused. Every member's
// scenario is now opened as its run opens it — including what only the flight's setup checks, such
// as a duration the trajectory cannot fly — before anything is written.
TEST(DistributedSweep, EveryMemberIsCheckedBeforeTheFirstFlies) {
  test::TempDir work;
  fs::copy_file(kCorridor, work.path() / "corridor.yaml");
  const auto refusal = [&](const std::string& vary) {
    const fs::path sweep_file = work.path() / "sweep.yaml";
    std::ofstream(sweep_file) << "base: corridor.yaml\ncount: 3\noutputs: d64\nvary:\n" << vary;
    const SweepSpec spec = read_sweep_file(sweep_file);
    std::unique_ptr<Communicator> comm = single_process_communicator();
    SweepRunOptions options;
    options.out = work.path() / "out";
    options.threads = 1;
    try {
      static_cast<void>(run_sweep(*comm, spec, options));
    } catch (const Error& e) {
      EXPECT_FALSE(fs::exists(options.out)) << e.what();
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string sweep_file = (work.path() / "sweep.yaml").string();
  const std::string corridor = (work.path() / "corridor.yaml").string();
  EXPECT_EQ(refusal("  trajectory.waypoints.speed_mps: {values: [40, fast]}\n"
                    "  trajectory.duration_s: {values: [1]}\n"),
            sweep_file + ": member 1: " + corridor +
                ": trajectory.waypoints.speed_mps: expected a number, got 'fast'");
  // The route ends at 69.6 s: member 2 asks for 80 s, which only the flight's setup finds out.
  const std::string too_long =
      refusal("  trajectory.duration_s: {values: [1, 1, 80]}\n  seed: {member: true}\n");
  EXPECT_EQ(too_long.rfind(sweep_file + ": member 2: ", 0), 0u) << too_long;
  EXPECT_NE(too_long.find("frames fit"), std::string::npos) << too_long;
  EXPECT_EQ(refusal("  trajectory.duration_s: {values: [1]}\n  seed: {member: true}\n"),
            "no error");
}

// Regression (issue 45): `owsim sweep` over a sweep file that names itself as its base left
// .owsim-sweep.json in the output folder.
TEST(DistributedSweep, ARefusedSweepWritesNothing) {
  test::TempDir work;
  std::ofstream(work.path() / "self.yaml") << "base: self.yaml\ncount: 2\nvary: {}\n";
  const test::CliResult self = test::run_cli({"sweep", "self.yaml", "--out", "out"}, work.path());
  EXPECT_EQ(self.exit_status, 1);
  EXPECT_EQ(
      self.err,
      "owsim: self.yaml:1: base: names this sweep file: the base is the scenario every member "
      "starts from\n");
  fs::copy_file(kCorridor, work.path() / "corridor.yaml");
  std::ofstream(work.path() / "bad.yaml")
      << "base: corridor.yaml\ncount: 2\nvary:\n  trajectory.duration_s: {values: [1, x]}\n";
  const test::CliResult bad = test::run_cli({"sweep", "bad.yaml", "--out", "out"}, work.path());
  EXPECT_EQ(bad.exit_status, 1);
  EXPECT_EQ(bad.err.rfind("owsim: bad.yaml: member 1: ", 0), 0u) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(fs::exists(work.path() / "out"));
}

}  // namespace
}  // namespace owsim
