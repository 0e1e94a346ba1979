// Protects `owsim info` (INTERFACE.md): a sound recording exits 0 and reports its frames, --json
// parses, a damaged one exits non-zero naming the problem, a bad file name is one stderr line.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "test_recording_check_fixture.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_status = -1;
  std::string out, err;
};

class CliInfo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fixture::fresh_directory(
        std::string("cli_info_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  static std::string quoted(const std::string& text) { return "'" + text + "'"; }

  CliRun owsim(const std::string& arguments) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string command = quoted(OWSIM_CLI_PATH) + " " + arguments + " >" +
                                quoted(out.string()) + " 2>" + quoted(err.string());
    const int status = std::system(command.c_str());
    CliRun run;
    run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = slurp(out);
    run.err = slurp(err);
    return run;
  }

  fs::path write_milows(const std::string& name, const std::vector<std::uint64_t>& words) {
    const fs::path path = dir_ / name;
    fixture::write_words<std::uint64_t>(path, words);
    return path;
  }

  fs::path dir_;
};

TEST_F(CliInfo, SoundMilowsRecordingExitsZeroAndReportsItsFrames) {
  const fs::path path = write_milows("flight.d64", fixture::milows_words(3));
  const CliRun run = owsim("info " + quoted(path.string()));
  EXPECT_EQ(run.exit_status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("3 complete frames"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("61056"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("problems: none"), std::string::npos) << run.out;
  EXPECT_TRUE(run.err.empty()) << run.err;
}

TEST_F(CliInfo, SoundHellasRecordingExitsZero) {
  const fs::path path = dir_ / "flight.hellas";
  fixture::write_words<std::uint32_t>(path, fixture::hellas_words(2));
  const CliRun run = owsim("info " + quoted(path.string()));
  EXPECT_EQ(run.exit_status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("HELLAS"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("2 complete frames"), std::string::npos) << run.out;
}

TEST_F(CliInfo, JsonParsesAndHasTheFields) {
  const fs::path path = write_milows("flight.d64", fixture::milows_words(3));
  const CliRun run = owsim("info " + quoted(path.string()) + " --json");
  ASSERT_EQ(run.exit_status, 0) << run.out << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json.at("format"), "d64");
  EXPECT_EQ(json.at("complete_frames"), 3);
  EXPECT_EQ(json.at("lines"), 477);
  EXPECT_EQ(json.at("pulses"), 61'056);
  EXPECT_EQ(json.at("words"), 61'056);
  EXPECT_EQ(json.at("trailing_bytes"), 0);
  EXPECT_EQ(json.at("ok"), true);
  EXPECT_EQ(json.at("problem_count"), 0);
  EXPECT_TRUE(json.at("problems").is_array());
  EXPECT_EQ(json.at("returns_per_fiber").size(), 128u);
  for (const char* key :
       {"counter1", "counter2", "reference_counter", "time", "encoder", "partial", "notes"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json.at("time").at("tick_s"), 100e-6);
}

TEST_F(CliInfo, MovedLineGateExitsNonZeroAndNamesTheProblem) {
  auto words = fixture::milows_words(2);
  const std::size_t w = 3 * fixture::kFibers + 127;
  words[w] &= ~(std::uint64_t{1} << 30);
  words[w + 1] |= std::uint64_t{1} << 30;
  const fs::path path = write_milows("moved.d64", words);
  const CliRun text = owsim("info " + quoted(path.string()));
  EXPECT_EQ(text.exit_status, 1) << text.out << text.err;
  EXPECT_NE(
      text.out.find("word " + std::to_string(w) + ": line reaches 128 pulses without a line gate"),
      std::string::npos)
      << text.out;
  const CliRun json_run = owsim("info " + quoted(path.string()) + " --json");
  EXPECT_EQ(json_run.exit_status, 1);
  const nlohmann::json json = nlohmann::json::parse(json_run.out);
  EXPECT_EQ(json.at("ok"), false);
  ASSERT_FALSE(json.at("problems").empty());
  EXPECT_EQ(json.at("problems")[0].at("word"), w);
  EXPECT_EQ(json.at("problems")[0].at("kind"), "line_length");
}

TEST_F(CliInfo, MissingFileIsOneStderrLineNamingIt) {
  const fs::path missing = dir_ / "no_such_flight.d64";
  const CliRun run = owsim("info " + quoted(missing.string()));
  EXPECT_NE(run.exit_status, 0);
  EXPECT_TRUE(run.out.empty()) << run.out;
  ASSERT_FALSE(run.err.empty());
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;  // exactly one line
  EXPECT_NE(run.err.find(missing.string()), std::string::npos) << run.err;
}

TEST_F(CliInfo, UnknownExtensionNeedsFormat) {
  const fs::path path = write_milows("flight.bin", fixture::milows_words(1));
  const CliRun refused = owsim("info " + quoted(path.string()));
  EXPECT_NE(refused.exit_status, 0);
  EXPECT_EQ(refused.err.find('\n'), refused.err.size() - 1) << refused.err;
  EXPECT_NE(refused.err.find(path.string()), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--format"), std::string::npos) << refused.err;

  const CliRun accepted = owsim("info " + quoted(path.string()) + " --format d64");
  EXPECT_EQ(accepted.exit_status, 0) << accepted.out << accepted.err;
  EXPECT_NE(accepted.out.find("1 complete frames"), std::string::npos) << accepted.out;

  // --format overrides the extension: 8-byte MilOWS words read as HELLAS words are nonsense.
  const CliRun as_hellas = owsim("info " + quoted(path.string()) + " --format hellas");
  EXPECT_EQ(as_hellas.exit_status, 1) << as_hellas.out;

  const CliRun bogus = owsim("info " + quoted(path.string()) + " --format las");
  EXPECT_NE(bogus.exit_status, 0);
}

}  // namespace
}  // namespace owsim
