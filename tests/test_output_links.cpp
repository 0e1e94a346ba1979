// Protects owsim's outputs against what is planted in a shared output folder, end to end through
// the built CLI (issue 45, family 1): a symbolic link, a hard link, a FIFO at an output's
// temporary name `NAME.partial` is never written through — by `owsim run`, `pd`, `view` — the file
// outside stays as it was and NAME becomes a regular file; a link where owsim makes a folder of its
// own (quicklook/, inputs/…, a sweep member's folder) is refused in one line, nothing written
// through it.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::read_whole_file;
using test::run_cli;
using test::TempDir;

const fs::path kExamples = fs::path(OWSIM_SOURCE_DIR) / "examples";

class OutputLinks : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(outside());
    std::ofstream(victim()) << "precious";
  }
  [[nodiscard]] fs::path outside() const { return work_ / "outside"; }
  [[nodiscard]] fs::path victim() const { return outside() / "victim.txt"; }
  // A symbolic link at `name`'s temporary in the work folder, to the victim.
  void plant_link(const std::string& name) const {
    fs::create_symlink(victim(), work_ / (name + ".partial"));
  }
  // `name` in the work folder is a regular file with one name, and no temporary is left.
  void expect_regular(const std::string& name) const {
    EXPECT_EQ(fs::symlink_status(work_ / name).type(), fs::file_type::regular) << name;
    EXPECT_EQ(fs::hard_link_count(work_ / name), 1u) << name;
    EXPECT_FALSE(fs::exists(fs::symlink_status(work_ / (name + ".partial")))) << name;
  }
  // The victim as it was, alone in its folder.
  void expect_victim_untouched() const {
    EXPECT_EQ(read_whole_file(victim()), "precious");
    EXPECT_EQ(fs::hard_link_count(victim()), 1u);
    EXPECT_EQ(std::distance(fs::directory_iterator(outside()), fs::directory_iterator()), 1);
  }

  TempDir work_{"owsim_output_links"};
};

TEST_F(OutputLinks, RunPdAndViewWriteNothingThroughWhatIsPlantedAtTheirTemporaries) {
  fs::create_directories(work_ / "a");
  plant_link("a/points.csv");
  fs::create_hard_link(victim(), work_ / "a/truth.csv.partial");
  ASSERT_EQ(::mkfifo((work_ / "a/summary.json.partial").c_str(), 0666), 0);
  const auto run = run_cli(
      {"run", (kExamples / "pylon_line.yaml").string(), "--out", "a", "--duration", "8", "--quiet"},
      work_.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  expect_victim_untouched();
  for (const char* name : {"a/points.csv", "a/truth.csv", "a/summary.json"}) expect_regular(name);
  EXPECT_EQ(read_whole_file(work_ / "a/points.csv").rfind("frame,", 0), 0u);

  plant_link("a/pd.csv");
  fs::create_symlink(outside() / "made.json", work_ / "a/pd.json.partial");  // dangling
  const auto pd = run_cli({"pd", "a"}, work_.path());
  ASSERT_EQ(pd.exit_status, 0) << pd.err;
  expect_victim_untouched();
  for (const char* name : {"a/pd.csv", "a/pd.json", "a/pd.svg"}) expect_regular(name);
  EXPECT_EQ(read_whole_file(work_ / "a/pd.csv").rfind("target,range_lo_m,", 0), 0u);

  plant_link("a/report.html");
  const auto view = run_cli({"view", "a"}, work_.path());
  ASSERT_EQ(view.exit_status, 0) << view.err;
  expect_victim_untouched();
  expect_regular("a/report.html");
}

// The scenario's input files are copied into inputs/1/…: a link at the folder's name is refused,
// one at a copy's temporary is not followed.
TEST_F(OutputLinks, TheRunFoldersInputCopiesAreNeverWrittenThroughALink) {
  const std::vector<std::string> run = {"run",       (kExamples / "hellsim_flight.yaml").string(),
                                        "--out",     "h",
                                        "--frames",  "2",
                                        "--outputs", "summary",
                                        "--quiet"};
  fs::create_directories(work_ / "h/inputs");
  fs::create_directory_symlink(outside(), work_ / "h/inputs/1");
  const auto refused = run_cli(run, work_.path());
  EXPECT_EQ(refused.exit_status, 1);
  EXPECT_EQ(refused.err,
            "owsim: h/inputs/1: cannot create the folder: it is a symbolic link (not followed)\n");
  expect_victim_untouched();

  fs::remove(work_ / "h/inputs/1");
  fs::create_directories(work_ / "h/inputs/1");
  plant_link("h/inputs/1/hellsim_turn_north.txt");
  const auto flown = run_cli(run, work_.path());
  ASSERT_EQ(flown.exit_status, 0) << flown.err;
  expect_victim_untouched();
  EXPECT_EQ(read_whole_file(work_ / "h/inputs/1/hellsim_turn_north.txt"),
            read_whole_file(kExamples / "data/hellsim_turn_north.txt"));
  EXPECT_EQ(fs::symlink_status(work_ / "h/inputs/1/hellsim_turn_north.txt").type(),
            fs::file_type::regular);
}

TEST_F(OutputLinks, AQuicklookFolderOrSweepMemberThatIsALinkIsRefused) {
  fs::create_directories(work_ / "q");
  fs::create_directory_symlink(outside(), work_ / "q/quicklook");
  const auto run = run_cli({"run", (kExamples / "pylon_line.yaml").string(), "--out", "q",
                            "--duration", "2", "--outputs", "quicklook", "--quiet"},
                           work_.path());
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_EQ(run.err,
            "owsim: q/quicklook: cannot create the folder: it is a symbolic link (not followed)\n");

  std::string base = read_whole_file(kExamples / "pylon_line.yaml");
  base.replace(base.find("duration_s: 30"), 14, "duration_s: 2");
  std::ofstream(work_ / "base.yaml") << base;
  std::ofstream(work_ / "sweep.yaml")
      << "base: base.yaml\ncount: 2\noutputs: summary\nvary:\n  seed: {member: true}\n";
  fs::create_directories(work_ / "s");
  fs::create_directory_symlink(outside(), work_ / "s/1");
  const auto sweep = run_cli({"sweep", "sweep.yaml", "--out", "s", "--quiet"}, work_.path());
  EXPECT_EQ(sweep.exit_status, 1);
  EXPECT_NE(sweep.err.find("owsim: s/1: cannot create the folder: it is a symbolic link (not "
                           "followed)\n"),
            std::string::npos)
      << sweep.err;
  expect_victim_untouched();
}

}  // namespace
}  // namespace owsim
