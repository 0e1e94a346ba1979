// Protects `owsim run --resume` end to end through the built CLI (INTERFACE.md, issue 7): a run
// killed with SIGKILL mid-flight leaves nothing under the final names, and resumed (with another
// thread count) it finishes byte-identical to an uninterrupted run — flight.d64, points.csv,
// points.las, points.ply, trajectory.csv, every quick-look PNG, and summary.json but for its
// wall-time figures; a resume with other options is a one-line error that keeps the checkpoint;
// --resume without a checkpoint starts from frame 0 and says so.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"
#include "io/run/run_checkpoint.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::TempDir;

// 200 corridor frames (of the 208 its route holds) take 3.3 s at 2 threads on the 2-core machine
// the tests run on (measured): long enough to kill a run after its first checkpoint (0.5 s in) and
// well before its end.
const std::string kFrames = "200";

std::string corridor() { return std::string(OWSIM_SOURCE_DIR) + "/examples/corridor.yaml"; }

// `owsim run corridor --out <folder> --frames kFrames --threads <threads> --quiet` and `extra`.
std::vector<std::string> run_arguments(const std::string& folder, const std::string& threads,
                                       const std::vector<std::string>& extra = {}) {
  std::vector<std::string> arguments = {"run",   corridor(),  "--out", folder,   "--frames",
                                        kFrames, "--threads", threads, "--quiet"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

// The first offset where the two files differ, or std::nullopt if their bytes are the same.
std::optional<std::uint64_t> first_difference(const fs::path& a, const fs::path& b) {
  std::ifstream in_a(a, std::ios::binary), in_b(b, std::ios::binary);
  if (!in_a || !in_b) return 0;
  std::vector<char> block_a(1 << 20), block_b(1 << 20);
  std::uint64_t offset = 0;
  while (true) {
    in_a.read(block_a.data(), static_cast<std::streamsize>(block_a.size()));
    in_b.read(block_b.data(), static_cast<std::streamsize>(block_b.size()));
    const std::streamsize got_a = in_a.gcount(), got_b = in_b.gcount();
    for (std::streamsize i = 0; i < std::min(got_a, got_b); ++i) {
      if (block_a[static_cast<std::size_t>(i)] != block_b[static_cast<std::size_t>(i)]) {
        return offset + static_cast<std::uint64_t>(i);
      }
    }
    if (got_a != got_b) return offset + static_cast<std::uint64_t>(std::min(got_a, got_b));
    if (got_a == 0) return std::nullopt;
    offset += static_cast<std::uint64_t>(got_a);
  }
}

void expect_same_bytes(const fs::path& reference, const fs::path& other) {
  ASSERT_TRUE(fs::exists(reference)) << reference;
  ASSERT_TRUE(fs::exists(other)) << other;
  const std::optional<std::uint64_t> at = first_difference(reference, other);
  EXPECT_FALSE(at.has_value()) << other << " differs from " << reference << " at byte " << *at;
}

// summary.json without the figures that depend on the wall clock and the thread count.
nlohmann::json summary_without_timing(const fs::path& path) {
  nlohmann::json summary = nlohmann::json::parse(test::read_whole_file(path));
  for (const char* key : {"setup_s", "wall_s", "pulses_per_s", "realtime_factor", "threads"}) {
    summary.erase(key);
  }
  return summary;
}

const std::vector<std::string> kFinalNames = {"flight.d64",       "points.csv",     "points.las",
                                              "points.ply",       "trajectory.csv", "summary.json",
                                              "quicklook/map.png"};

// Starts `owsim arguments…` in `work_dir` with its output thrown away, and kills it with SIGKILL
// as soon as the checkpoint in `work_dir/folder` holds a complete frame. Fails the test if the run
// ends first. Returns the frames the checkpoint held.
std::int64_t run_and_kill(const std::vector<std::string>& arguments, const fs::path& work_dir,
                          const std::string& folder) {
  std::vector<std::string> argv_text = {OWSIM_CLI_PATH};
  argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& text : argv_text) argv.push_back(text.data());
  argv.push_back(nullptr);
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null < 0 || ::dup2(null, STDOUT_FILENO) < 0 || ::dup2(null, STDERR_FILENO) < 0 ||
        ::chdir(work_dir.c_str()) != 0) {
      ::_exit(126);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  const fs::path checkpoint = run_checkpoint_path(work_dir / folder);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::int64_t frames_done = 0;
  while (frames_done < 1 && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    int status = 0;
    if (::waitpid(child, &status, WNOHANG) == child) {
      ADD_FAILURE() << "the run ended (status " << status << ") before a checkpoint was seen";
      return 0;
    }
    try {
      if (const auto read = read_run_checkpoint(checkpoint)) frames_done = read->frames_done;
    } catch (const std::exception&) {  // not there yet
    }
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
      << "the run was not killed mid-flight (status " << status << ")";
  return frames_done;
}

// What a SIGKILL leaves: temporaries (with bytes after the checkpoint, which resume cuts off),
// the checkpoint, nothing under a final name.
void expect_killed_state(const fs::path& folder) {
  for (const std::string& name : kFinalNames) {
    EXPECT_FALSE(fs::exists(folder / name)) << name << " appeared before the run finished";
  }
  for (const std::string name : {"flight.d64", "points.csv", "points.las", "points.ply"}) {
    const fs::path partial = folder / (name + ".partial");
    ASSERT_TRUE(fs::exists(partial)) << partial;
    std::ofstream(partial, std::ios::binary | std::ios::app) << "written after the checkpoint";
  }
  EXPECT_TRUE(fs::exists(run_checkpoint_path(folder)));
}

TEST(RunResume, KilledRunResumesToTheUninterruptedBytes) {
  const TempDir work("owsim_run_resume");
  const test::CliResult reference = run_cli(run_arguments("reference", "2"), work.path());
  ASSERT_EQ(reference.exit_status, 0) << reference.command << "\n" << reference.err;

  const std::int64_t done = run_and_kill(run_arguments("resumed", "1"), work.path(), "resumed");
  ASSERT_GE(done, 1);
  ASSERT_LT(done, std::stoll(kFrames));
  expect_killed_state(work / "resumed");

  const test::CliResult resumed = run_cli(run_arguments("resumed", "2", {"--resume"}), work.path());
  ASSERT_EQ(resumed.exit_status, 0) << resumed.command << "\n" << resumed.err;
  EXPECT_EQ(resumed.err, "");

  for (const std::string name : {"flight.d64", "points.csv", "points.las", "points.ply",
                                 "trajectory.csv", "truth.csv", "scenario.yaml"}) {
    expect_same_bytes(work / "reference" / name, work / "resumed" / name);
  }
  std::vector<std::string> pngs;
  for (const auto& entry : fs::directory_iterator(work / "reference" / "quicklook")) {
    pngs.push_back(entry.path().filename().string());
    expect_same_bytes(entry.path(), work / "resumed" / "quicklook" / pngs.back());
  }
  EXPECT_EQ(pngs.size(), 21u);  // frames 0, 10, …, 190 and the map
  EXPECT_EQ(summary_without_timing(work / "resumed" / "summary.json"),
            summary_without_timing(work / "reference" / "summary.json"));
  for (const auto& entry : fs::recursive_directory_iterator(work / "resumed")) {
    EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  }
  EXPECT_FALSE(fs::exists(run_checkpoint_path(work / "resumed")));
}

// The detector's state is no checkpoint of its own: a resumed run replays the words it kept
// through the detector, so detections.csv is the uninterrupted run's bytes (issue 69).
TEST(RunResume, KilledRunResumesToTheUninterruptedDetections) {
  const TempDir work("owsim_run_resume");
  const std::vector<std::string> outputs = {"--outputs", "d64,detections"};
  const test::CliResult reference = run_cli(run_arguments("reference", "2", outputs), work.path());
  ASSERT_EQ(reference.exit_status, 0) << reference.command << "\n" << reference.err;
  const std::int64_t done =
      run_and_kill(run_arguments("resumed", "1", outputs), work.path(), "resumed");
  ASSERT_GE(done, 1);
  ASSERT_LT(done, std::stoll(kFrames));
  EXPECT_FALSE(fs::exists(work / "resumed" / "detections.csv"));

  std::vector<std::string> again = outputs;
  again.push_back("--resume");
  const test::CliResult resumed = run_cli(run_arguments("resumed", "2", again), work.path());
  ASSERT_EQ(resumed.exit_status, 0) << resumed.command << "\n" << resumed.err;
  EXPECT_GT(fs::file_size(work / "reference" / "detections.csv"), 1000u);
  expect_same_bytes(work / "reference" / "detections.csv", work / "resumed" / "detections.csv");
  expect_same_bytes(work / "reference" / "flight.d64", work / "resumed" / "flight.d64");
}

TEST(RunResume, ResumeWithAnotherSeedIsRefusedAndKeepsTheCheckpoint) {
  const TempDir work("owsim_run_resume");
  ASSERT_GE(run_and_kill(run_arguments("out", "2"), work.path(), "out"), 1);
  const fs::path checkpoint = run_checkpoint_path(work / "out");
  const std::string before = test::read_whole_file(checkpoint);

  const test::CliResult other =
      run_cli(run_arguments("out", "2", {"--resume", "--seed", "7"}), work.path());
  EXPECT_NE(other.exit_status, 0);
  EXPECT_EQ(other.err, "owsim: " + checkpoint.lexically_relative(work.path()).string() +
                           ": written by a different run: seed was 2024, now 7 (run without "
                           "--resume to start over)\n");
  for (const std::string& name : kFinalNames) EXPECT_FALSE(fs::exists(work / "out" / name)) << name;
  EXPECT_EQ(test::read_whole_file(checkpoint), before);
  EXPECT_TRUE(fs::exists(work / "out" / "flight.d64.partial"));
}

TEST(RunResume, ResumeWithoutACheckpointStartsFromFrameZero) {
  const TempDir work("owsim_run_resume");
  const std::vector<std::string> base = {"run",     corridor(),  "--frames", "6",
                                         "--quiet", "--threads", "2"};
  std::vector<std::string> reference = base;
  reference.insert(reference.end(), {"--out", "reference"});
  ASSERT_EQ(run_cli(reference, work.path()).exit_status, 0);

  // A temporary of an earlier run, without its checkpoint: not to be continued.
  fs::create_directories(work / "fresh");
  std::ofstream(work / "fresh" / "flight.d64.partial", std::ios::binary) << "stale bytes";
  std::vector<std::string> fresh = base;
  fresh.insert(fresh.end(), {"--out", "fresh", "--resume"});
  const test::CliResult result = run_cli(fresh, work.path());
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_EQ(result.err, "owsim run --resume: no checkpoint fresh/" +
                            std::string(kRunCheckpointFileName) + ": starting from frame 0\n");
  for (const std::string name :
       {"flight.d64", "points.csv", "points.las", "points.ply", "trajectory.csv"}) {
    expect_same_bytes(work / "reference" / name, work / "fresh" / name);
  }
  EXPECT_FALSE(fs::exists(work / "fresh" / "flight.d64.partial"));
}

// owsim before issue 19 kept a JSON checkpoint, .owsim-resume.json: --resume refuses it with one
// line and writes nothing; a run without --resume starts over and removes it.
TEST(RunResume, AJsonCheckpointOfAnEarlierOwsimIsRefusedInOneLine) {
  const TempDir work("owsim_run_resume");
  fs::create_directories(work / "old");
  std::ofstream(work / "old" / ".owsim-resume.json") << "owsim run checkpoint fnv1a64 0\n{}\n";
  const std::vector<std::string> base = {"run",       corridor(), "--frames", "3",  "--quiet",
                                         "--threads", "2",        "--out",    "old"};
  std::vector<std::string> resume = base;
  resume.push_back("--resume");
  const test::CliResult refused = run_cli(resume, work.path());
  EXPECT_EQ(refused.exit_status, 1);
  EXPECT_EQ(refused.err,
            "owsim: old/.owsim-resume.json: a JSON checkpoint of an earlier owsim, which this one "
            "cannot resume; run without --resume to start over\n");
  EXPECT_FALSE(fs::exists(work / "old" / "flight.d64"));
  ASSERT_EQ(run_cli(base, work.path()).exit_status, 0);
  EXPECT_TRUE(fs::exists(work / "old" / "flight.d64"));
  EXPECT_FALSE(fs::exists(work / "old" / ".owsim-resume.json"));
}

}  // namespace
}  // namespace owsim
