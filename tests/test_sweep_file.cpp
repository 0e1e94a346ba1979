// The sweep file (io/sweep/sweep_file.hpp): what it reads, the draws of each distribution against
// their moments, draws keyed by (seed, member, key) alone, the member scenarios the loader reads
// back with the drawn values, and one line naming file, line and key for every bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "geometry/error.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/sweep/sweep_file.hpp"
#include "tests/cli_runner.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(OWSIM_SOURCE_DIR) / "examples";

SweepSpec example() { return read_sweep_file(kExamples / "corridor_sweep.yaml"); }

std::string error_of(const std::string& text) {
  const test::TempDir work;
  fs::copy_file(kExamples / "corridor.yaml", work.path() / "corridor.yaml");
  const fs::path file = work.path() / "sweep.yaml";
  std::ofstream(file) << text;
  try {
    static_cast<void>(read_sweep_file(file));
  } catch (const Error& e) {
    const std::string message = e.what();
    return message.substr(message.find("sweep.yaml"));
  }
  return "no error";
}

// A sweep file reads only its own folder tree: each test copies the base beside it.
const std::string kHead = "base: corridor.yaml\ncount: 4\n";

TEST(SweepFile, ReadsTheExample) {
  const SweepSpec spec = example();
  EXPECT_EQ(fs::weakly_canonical(spec.base), kExamples / "corridor.yaml");
  EXPECT_EQ(spec.count, 20);
  EXPECT_EQ(spec.seed, 7u);
  EXPECT_EQ(spec.outputs, "d64,summary");
  ASSERT_EQ(spec.vary.size(), 4u);
  EXPECT_EQ(spec.vary[0].key, "scene.spans[0].conductor.diameter_mm");
  EXPECT_EQ(spec.vary[0].kind, SweepVariation::Kind::uniform);
  EXPECT_EQ(spec.vary[0].a, 5);
  EXPECT_EQ(spec.vary[0].b, 30);
  EXPECT_EQ(spec.vary[1].kind, SweepVariation::Kind::choice);
  EXPECT_EQ(spec.vary[1].items, (std::vector<std::string>{"30", "35", "40"}));
  EXPECT_EQ(spec.vary[2].kind, SweepVariation::Kind::normal);
  EXPECT_EQ(spec.vary[3].kind, SweepVariation::Kind::member);
  EXPECT_EQ(member_folder_name(spec, 7), "07");
  EXPECT_EQ(member_folder_name(spec, 19), "19");
}

TEST(SweepFile, DrawsFollowTheirDistributions) {
  SweepSpec spec = example();
  spec.count = 6000;
  double sum_u = 0, sum_n = 0, sum_n2 = 0;
  std::map<std::string, int> picks;
  for (std::int64_t m = 0; m < spec.count; ++m) {
    const std::vector<std::string> values = member_values(spec, m);
    const double u = std::stod(values[0]);
    ASSERT_GE(u, 5);
    ASSERT_LT(u, 30);
    sum_u += u;
    const double n = std::stod(values[2]);
    sum_n += n;
    sum_n2 += n * n;
    ++picks[values[1]];
    ASSERT_EQ(values[3], std::to_string(m));
  }
  const double count = static_cast<double>(spec.count);
  // Means within 4 standard errors: uniform σ = 25/√12, normal σ = 1.
  EXPECT_NEAR(sum_u / count, 17.5, 4 * 25 / std::sqrt(12.0) / std::sqrt(count));
  const double mean = sum_n / count;
  EXPECT_NEAR(mean, -4, 4 / std::sqrt(count));
  EXPECT_NEAR(std::sqrt(sum_n2 / count - mean * mean), 1, 4 / std::sqrt(2 * count));
  ASSERT_EQ(picks.size(), 3u);
  for (const auto& [value, n] : picks) EXPECT_NEAR(n / count, 1.0 / 3, 0.025) << value;
}

TEST(SweepFile, AMembersDrawsDependOnlyOnSeedMemberAndKey) {
  SweepSpec spec = example();
  const std::vector<std::string> before = member_values(spec, 13);
  spec.count = 1'000'000;                  // more members
  spec.vary.erase(spec.vary.begin() + 1);  // another key gone
  const std::vector<std::string> after = member_values(spec, 13);
  EXPECT_EQ(after[0], before[0]);
  EXPECT_EQ(after[1], before[2]);
  spec.seed = 8;
  EXPECT_NE(member_values(spec, 13)[0], before[0]);
  EXPECT_NE(member_values(spec, 12)[0], before[0]);
}

TEST(SweepFile, ValuesTakeTheirItemsInTurn) {
  test::TempDir work;
  fs::copy_file(kExamples / "corridor.yaml", work.path() / "corridor.yaml");
  const fs::path file = work.path() / "sweep.yaml";
  std::ofstream(file) << kHead << "vary:\n  sensor.model: {values: [milows, hellas, milows]}\n";
  const SweepSpec spec = read_sweep_file(file);
  EXPECT_EQ(member_values(spec, 0)[0], "milows");
  EXPECT_EQ(member_values(spec, 1)[0], "hellas");
  EXPECT_EQ(member_values(spec, 4)[0], "hellas");
}

TEST(SweepFile, MemberScenariosCarryTheDrawnValues) {
  const SweepSpec spec = example();
  for (const std::int64_t m : {0, 5, 19}) {
    const std::vector<std::string> values = member_values(spec, m);
    const Scenario scenario = load_scenario_text(member_scenario_text(spec, m), spec.base);
    EXPECT_DOUBLE_EQ(scenario.scene.spans.at(0).conductor_diameter_m, std::stod(values[0]) / 1000);
    EXPECT_DOUBLE_EQ(scenario.scene.spans.at(1).conductor_diameter_m, 0.021);  // untouched
    EXPECT_EQ(scenario.trajectory.speed_mps, std::stod(values[1]));
    EXPECT_EQ(scenario.mount.pitch_deg, std::stod(values[2]));
    EXPECT_EQ(scenario.seed, static_cast<std::uint64_t>(m));
    EXPECT_EQ(scenario.name, "corridor");
  }
}

TEST(SweepFile, BadInputNamesFileLineAndKey) {
  EXPECT_EQ(error_of(kHead + "vary:\n  seed: {gauss: [1, 2]}\n"),
            "sweep.yaml:4: vary.seed: expected one of uniform, normal, choice, values, member");
  EXPECT_EQ(error_of(kHead + "vary:\n  seed: {uniform: [3, 1]}\n"),
            "sweep.yaml:4: vary.seed.uniform: [a, b] needs a < b");
  EXPECT_EQ(error_of(kHead + "vary:\n  seed: {choice: []}\n"),
            "sweep.yaml:4: vary.seed.choice: expected a list of one or more items");
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spans[x]: {member: true}\n"),
            "sweep.yaml:4: vary.scene.spans[x]: expected a key path of dot-separated keys and [i] "
            "indices");
  EXPECT_NE(error_of("base: nowhere.yaml\ncount: 2\nvary: {}\n").find("sweep.yaml:1: base:"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "vary: {}\nextra: 1\n").find("sweep.yaml:4: extra: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("base: corridor.yaml\ncount: 0\nvary: {}\n").find("sweep.yaml:2: count:"),
            std::string::npos);
}

// A key path is checked against the base scenario when the sweep file is read, before anything
// is written.
TEST(SweepFile, AKeyPathThatLeadsNowhereIsNamed) {
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spans[40].conductor.diameter_mm: {member: true}\n"),
            "sweep.yaml:4: vary.scene.spans[40].conductor.diameter_mm: the base scenario has no "
            "'scene.spans[40]'");
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spanz[0].id: {member: true}\n"),
            "sweep.yaml:4: vary.scene.spanz[0].id: the base scenario has no 'scene.spanz'");
}

// Regression (issue 45): an index past size_t (std::from_chars's out-of-range left it 0) varied
// spans[0]; "[0" with no "]" read past the key, and text after "]" was ignored.
TEST(SweepFile, ListIndicesAreWholeNumbersThatFit) {
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spans[99999999999999999999999].id: {member: true}\n"),
            "sweep.yaml:4: vary.scene.spans[99999999999999999999999].id: list index "
            "99999999999999999999999 is too large");
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spans[18446744073709551616].id: {member: true}\n"),
            "sweep.yaml:4: vary.scene.spans[18446744073709551616].id: list index "
            "18446744073709551616 is too large");
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spans[18446744073709551615].id: {member: true}\n"),
            "sweep.yaml:4: vary.scene.spans[18446744073709551615].id: the base scenario has no "
            "'scene.spans[18446744073709551615]'");
  for (const std::string key : {"scene.spans[0", "scene.spans[0]x.id", "scene.spans[].id",
                                "scene.spans[-1].id", "scene.spans[+1].id", "scene.spans]0[.id",
                                "scene..spans", "scene.[0]", "scene.spans[0]]"}) {
    EXPECT_EQ(
        error_of(kHead + "vary:\n  '" + key + "': {member: true}\n"),
        "sweep.yaml:4: vary." + key + ": expected a key path of dot-separated keys and [i] indices")
        << key;
  }
  EXPECT_EQ(error_of(kHead + "vary:\n  scene.spans[1].id: {values: [x]}\n"), "no error");
}

// Regression (issue 45): a sweep file naming itself as its base was read, and `owsim sweep` left
// .owsim-sweep.json behind before member 0 failed.
TEST(SweepFile, ABaseThatIsTheSweepFileItselfIsRefused) {
  EXPECT_EQ(error_of("base: sweep.yaml\ncount: 2\nvary: {}\n"),
            "sweep.yaml:1: base: names this sweep file: the base is the scenario every member "
            "starts from");
  EXPECT_EQ(error_of("base: ./sweep.yaml\ncount: 2\nvary: {}\n"),
            "sweep.yaml:1: base: names this sweep file: the base is the scenario every member "
            "starts from");
}

}  // namespace
}  // namespace owsim
