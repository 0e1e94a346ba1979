// Protects `owsim pattern` (INTERFACE.md "owsim pattern columns"): the CSV header and row count,
// the values against the library's scan pattern, HELLAS and frame options, and bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

struct CliRun {
  int exit_status = -1;
  std::string out;
};

CliRun run_owsim(const std::string& arguments) {
  const std::string command = std::string(OWSIM_CLI_PATH) + " " + arguments + " 2>/dev/null";
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char chunk[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(chunk, 1, sizeof chunk, pipe)) > 0) run.out.append(chunk, n);
  const int status = pclose(pipe);
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

constexpr const char* kHeader = "pulse,line,fiber,time_s,alpha_deg,beta_deg,encoder,fg,lg,movdir";

enum Column { kPulse, kLine, kFiber, kTime, kAlpha, kBeta, kEncoder, kFg, kLg, kMovDir, kColumns };

std::vector<std::vector<std::string>> rows_of(const CliRun& run) {
  std::vector<std::vector<std::string>> rows;
  const std::vector<std::string> lines = split(run.out, '\n');
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (!lines[i].empty()) rows.push_back(split(lines[i], ','));
  }
  return rows;
}

TEST(CliPattern, DefaultFrameMatchesTheLibrary) {
  const CliRun run = run_owsim("pattern");
  ASSERT_EQ(run.exit_status, 0);
  ASSERT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 20'353);  // header + 20,352 pulses
  ASSERT_EQ(run.out.back(), '\n');
  EXPECT_EQ(run.out.substr(0, run.out.find('\n')), kHeader);
  const auto rows = rows_of(run);
  ASSERT_EQ(rows.size(), 20'352u);

  ASSERT_EQ(rows[0].size(), static_cast<std::size_t>(kColumns));
  EXPECT_EQ(rows[0][kFiber], "1");
  EXPECT_EQ(std::stod(rows[0][kAlpha]), -21.0);

  const ScanParams p;
  const FrameSweep sweep = frame_sweep(p, 0, 0);
  int fg = 0, lg = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& row = rows[k];
    ASSERT_EQ(row.size(), static_cast<std::size_t>(kColumns)) << "row " << k;
    const Pulse pulse = pulse_of_frame(p, sweep, static_cast<int>(k));
    ASSERT_EQ(std::stoi(row[kPulse]), pulse.index);
    ASSERT_EQ(std::stoi(row[kLine]), pulse.line);
    ASSERT_EQ(std::stoi(row[kFiber]), pulse.fiber);
    ASSERT_NEAR(std::stod(row[kTime]), pulse.time_s, 5e-10);
    if (pulse.reference) {
      ASSERT_TRUE(row[kAlpha].empty()) << "row " << k;
    } else {
      ASSERT_NEAR(std::stod(row[kAlpha]), pulse.alpha_deg, 5e-7);
    }
    ASSERT_NEAR(std::stod(row[kBeta]), pulse.beta_deg, 5e-7);
    ASSERT_EQ(std::stoi(row[kEncoder]), pulse.encoder);
    ASSERT_EQ(row[kFg], k == 20'351 ? "1" : "0");
    ASSERT_EQ(row[kLg], k % 128 == 127 ? "1" : "0");
    ASSERT_EQ(row[kMovDir], "0");
    fg += row[kFg] == "1";
    lg += row[kLg] == "1";
  }
  EXPECT_EQ(fg, 1);
  EXPECT_EQ(lg, 159);
  EXPECT_NEAR(std::stod(rows[0][kBeta]) + 0.134, -18.0, 0.1143);  // sweeps up from −18°
}

TEST(CliPattern, HellasHasNoEncoder) {
  const CliRun run = run_owsim("pattern --sensor hellas");
  ASSERT_EQ(run.exit_status, 0);
  const auto rows = rows_of(run);
  ASSERT_EQ(rows.size(), 20'352u);
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), static_cast<std::size_t>(kColumns));
    ASSERT_TRUE(row[kEncoder].empty());
  }
  EXPECT_EQ(rows.back()[kFg], "1");
  EXPECT_EQ(rows[127][kLg], "1");
}

TEST(CliPattern, FrameOneFallsAndStartsLater) {
  const CliRun run = run_owsim("pattern --frame 1 --seed 3");
  ASSERT_EQ(run.exit_status, 0);
  const auto rows = rows_of(run);
  ASSERT_EQ(rows.size(), 20'352u);
  for (const auto& row : rows) ASSERT_EQ(row[kMovDir], "1");
  EXPECT_NEAR(std::stod(rows[0][kTime]), 20'352.0 / 61'111.0, 5e-10);
  const ScanParams p;
  const FrameSweep sweep = frame_sweep(p, 3, 1);
  EXPECT_NEAR(std::stod(rows[500][kBeta]), pulse_of_frame(p, sweep, 500).beta_deg, 5e-7);
  EXPECT_GT(std::stod(rows[0][kBeta]), std::stod(rows[20'350][kBeta]));
}

TEST(CliPattern, SeedMovesTheSweep) {
  const auto a = rows_of(run_owsim("pattern --seed 1"));
  const auto b = rows_of(run_owsim("pattern --seed 2"));
  ASSERT_EQ(a.size(), 20'352u);
  ASSERT_EQ(b.size(), 20'352u);
  EXPECT_NE(a[0][kBeta], b[0][kBeta]);
  EXPECT_EQ(a[0][kAlpha], b[0][kAlpha]);
  EXPECT_EQ(a[0][kTime], b[0][kTime]);
}

TEST(CliPattern, BadInputFails) {
  EXPECT_NE(run_owsim("pattern --sensor foo").exit_status, 0);
  EXPECT_NE(run_owsim("pattern --frame -1").exit_status, 0);
  EXPECT_NE(run_owsim("pattern --frame abc").exit_status, 0);
  EXPECT_NE(run_owsim("pattern --seed -4").exit_status, 0);
  EXPECT_NE(run_owsim("pattern --frame 999999999999999999").exit_status, 0);
  const CliRun foo = run_owsim("pattern --sensor foo");
  EXPECT_TRUE(foo.out.empty());
}

}  // namespace
}  // namespace owsim
