// `owsim roc` end to end (INTERFACE.md "Receiver noise and sunlight", docs/evidence.md "owsim
// roc"): over a sweep folder built by hand — members with known windows, false returns, a summary
// from before the receiver had noise, values written two ways, a text-valued key — every cell of
// roc.csv and roc.json against counts made by hand and against an independent recount
// (tests/oracles/roc_oracle.py: numpy windows, scipy's beta quantiles to 1e-9, roc.svg parsed as
// XML with one point per value); each row's windows are exactly those `owsim pd` counts over the
// same members; a real sweep over two thresholds agrees with the recount too and shows in `owsim
// view`'s page; bad keys, folders and options are refused in one line with nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "csv_rows.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::csv_rows;
using test::run_cli;
using test::TempDir;

const fs::path kRocSource = OWSIM_SOURCE_DIR;

// One hand-made member: its values, flight length and false returns, and the wire's truth.
struct Member {
  std::string threshold;                       // as sweep.csv holds it
  std::string noise;                           // sensor.receiver.noise, a text-valued key
  int frames = 20;                             // of 0.25 s: a 1 s window is 4 frames
  std::optional<std::uint64_t> false_returns;  // none: a summary from before the noise class
  int in_view_from = 0;                        // wire/1 in view from this frame (20: never)
  std::map<int, int> returns;                  // wire/1's returns by frame
  bool second_wire = false;                    // wire/2, always in view at 750 m, never returned
};

// Members 0…7 (docs in each line: wire/1's windows starting at 700–800 m, K = 1, W = 1 s; its
// range is 900 − 20·f m, so frames 6…10 start in the bin).
const std::vector<Member> kMembers = {
    {"0.003", "on", 20, 0, 0, {{9, 1}, {12, 1}}},                                     // 5 of 5
    {"2.9e-3", "on", 20, 30, 0, {{6, 1}, {7, 1}, {8, 1}, {9, 1}, {10, 1}, {11, 1}}},  // 5 of 5
    {"0.005", "off", 20, std::nullopt, 20, {{9, 3}}},   // never in view: none
    {"0.003", "off", 20, std::nullopt, 8, {}},          // f = 8, 9, 10: 0 of 3
    {"0.0029", "on", 20, 12, 0, {{13, 1}}},             // f = 10 only: 1 of 5
    {"5e-3", "on", 20, 7, 20, {}},                      // never in view: none
    {"0.004", "on", 20, 3, 0, {{7, 1}, {8, 1}}, true},  // 3 of 5 (2 of 5 for K = 2); wire/2 0 of 17
    {"0.004", "off", 12, 5, 0, {{11, 2}}},              // f ≤ 8 fit: 1 of 3
};

void write_member(const fs::path& folder, const Member& member) {
  fs::create_directories(folder);
  nlohmann::json summary = {{"scenario", "hand-made"},
                            {"frames", member.frames},
                            {"frame_period_s", 0.25},
                            {"pulses", member.frames * 1000},
                            {"second_returns", 0},
                            {"returns", {{"wire", 0}, {"pole", 0}, {"tree", 0}, {"ground", 0}}},
                            {"objects", nlohmann::json::array()}};
  if (member.false_returns) summary["returns"]["noise"] = *member.false_returns;
  std::ofstream(folder / "summary.json") << summary.dump(2);
  std::ofstream truth(folder / "truth.csv");
  truth << "frame,time_s,object,class,range_m,alpha_deg,beta_deg,in_view,returns,"
           "closing_speed_mps,time_to_reach_s\n";
  for (int f = 0; f < member.frames; ++f) {
    const auto returns = member.returns.find(f);
    truth << f << ',' << 0.125 + 0.25 * f << ",wire/1,wire," << 900 - 20 * f << ",0,0,"
          << (f >= member.in_view_from ? 1 : 0) << ','
          << (returns == member.returns.end() ? 0 : returns->second) << ",80,1\n";
    if (member.second_wire) {
      truth << f << ',' << 0.125 + 0.25 * f << ",wire/2,wire,750,0,0,1,0,0,\n";
    }
    // A pole in the bin with returns everywhere: not a wire, never counted.
    truth << f << ',' << 0.125 + 0.25 * f << ",pole/1,pole,740,0,0,1,5,0,\n";
  }
}

std::string sweep_header() {
  return "member,sensor.threshold,sensor.receiver.noise,seed,frames,pulses,returns_wire,"
         "returns_pole,returns_tree,returns_ground,returns_noise,second_returns\n";
}

std::string sweep_row(std::size_t m) {
  const Member& member = kMembers[m];
  return std::to_string(m) + "," + member.threshold + "," + member.noise + "," + std::to_string(m) +
         "," + std::to_string(member.frames) + "," + std::to_string(member.frames * 1000) +
         ",0,0,0,0," + std::to_string(member.false_returns.value_or(0)) + ",0\n";
}

// The hand-made sweep in `folder`: all members, or those listed (with their own numbers).
void write_sweep(const fs::path& folder, const std::vector<std::size_t>& members) {
  fs::create_directories(folder);
  std::ofstream table(folder / "sweep.csv");
  table << sweep_header();
  for (const std::size_t m : members) {
    table << sweep_row(m);
    write_member(folder / std::to_string(m), kMembers[m]);
  }
}

std::vector<std::size_t> all_members() {
  std::vector<std::size_t> members(kMembers.size());
  for (std::size_t m = 0; m < members.size(); ++m) members[m] = m;
  return members;
}

std::string oracle(const fs::path& sweep, const fs::path& out, const std::string& arguments) {
  return test::run_python_file(
      kRocSource / "tests/oracles/roc_oracle.py",
      {.arguments = sweep.string() + " " + out.string() + " " + arguments});
}

// Each row's windows, detected windows, Pd and bounds are, cell for cell, what `owsim pd
// --bins LO:HI:HI−LO` writes over a sweep of that row's members alone.
void expect_pd_counts_the_same(
    const fs::path& work, const fs::path& roc_csv,
    const std::vector<std::vector<std::size_t>>& groups,
    const std::function<void(const fs::path&, const std::vector<std::size_t>&)>& copy,
    const std::vector<std::string>& pd_arguments) {
  const auto roc = csv_rows(roc_csv);
  ASSERT_EQ(roc.size(), groups.size() + 1);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const fs::path part = work / ("part" + std::to_string(g));
    copy(part, groups[g]);
    std::vector<std::string> arguments = {"pd", part.string(), "--quiet"};
    arguments.insert(arguments.end(), pd_arguments.begin(), pd_arguments.end());
    const auto pd = run_cli(arguments, work);
    ASSERT_EQ(pd.exit_status, 0) << pd.err;
    const auto bins = csv_rows(part / "pd.csv");
    ASSERT_EQ(bins.size(), 2u) << "one bin";
    // pd.csv: target,lo,hi,windows,windows_detected,pd_window,lo,hi; roc.csv: value,members,…
    for (std::size_t c = 0; c < 5; ++c) {
      EXPECT_EQ(roc[g + 1][2 + c], bins[1][3 + c]) << "row " << g << " column " << roc[0][2 + c];
    }
  }
}

TEST(RocCli, AHandMadeSweepGivesTheRowsCountedByHandAndByAnIndependentRecount) {
  const TempDir work("owsim_roc");
  write_sweep(work / "sweep", all_members());
  const auto roc = run_cli({"roc", "sweep"}, work.path());
  ASSERT_EQ(roc.exit_status, 0) << roc.err;
  EXPECT_NE(roc.err.find("class:wire: 4 values of sensor.threshold over 8 flights"),
            std::string::npos)
      << roc.err;
  const auto rows = csv_rows(work / "sweep/roc.csv");
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"value", "members", "windows", "windows_detected",
                                               "pd_window", "pd_window_lo", "pd_window_hi",
                                               "pulses", "false_returns", "false_returns_per_s"}));
  // By hand (the counts beside kMembers): numbers pool however written, sorted by number (as
  // text "2.9e-3" would come last), labelled as the first member wrote them.
  const auto expect = [&](std::size_t r, std::vector<std::string> cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c] != "*") EXPECT_EQ(rows[r][c], cells[c]) << "row " << r << " " << rows[0][c];
    }
  };
  expect(1, {"2.9e-3", "2", "10", "6", "0.600000000000", "*", "*", "40000", "42", "4.2"});
  expect(2, {"0.003", "2", "8", "5", "0.625000000000", "*", "*", "40000", "0", "0"});
  expect(3, {"0.004", "2", "25", "4", "0.160000000000", "*", "*", "32000", "8", "1"});
  expect(4, {"0.005", "2", "0", "0", "", "", "", "40000", "7", "0.7"});
  EXPECT_EQ(oracle(work / "sweep", work / "sweep", "sensor.threshold 700 800 1 1 0.95 class:wire")
                .find("roc oracle: 4 values, 43 windows agree"),
            0u);

  // Another criterion, target, bin and confidence, into another folder.
  const auto strict =
      run_cli({"roc", "sweep", "--target", "wire/1", "--returns", "2", "--window-s", "1", "--range",
               "680:780", "--confidence", "0.9", "--out", "strict", "--quiet"},
              work.path());
  ASSERT_EQ(strict.exit_status, 0) << strict.err;
  EXPECT_TRUE(strict.err.empty()) << strict.err;
  EXPECT_NE(oracle(work / "sweep", work / "strict", "sensor.threshold 680 780 2 1 0.9 wire/1")
                .find("agree"),
            std::string::npos);
  const nlohmann::json json =
      nlohmann::json::parse(test::read_whole_file(work / "strict/roc.json"));
  EXPECT_EQ(json.at("interval"), "clopper-pearson");
  EXPECT_EQ(json.at("range_m"), (std::vector<double>{680, 780}));
  EXPECT_EQ(json.at("rows").at(0).at("value"), 0.0029);  // a number where every value is one

  // A text-valued key: rows by spelling, sorted as text.
  const auto by_text = run_cli(
      {"roc", "sweep", "--by", "sensor.receiver.noise", "--out", "text", "--quiet"}, work.path());
  ASSERT_EQ(by_text.exit_status, 0) << by_text.err;
  EXPECT_NE(
      oracle(work / "sweep", work / "text", "sensor.receiver.noise 700 800 1 1 0.95 class:wire")
          .find("roc oracle: 2 values"),
      std::string::npos);
  const auto text_rows = csv_rows(work / "text/roc.csv");
  ASSERT_EQ(text_rows.size(), 3u);
  EXPECT_EQ(text_rows[1][0], "off");
  EXPECT_EQ(text_rows[2][0], "on");
  EXPECT_EQ(nlohmann::json::parse(test::read_whole_file(work / "text/roc.json"))
                .at("rows")
                .at(0)
                .at("value"),
            "off");
}

TEST(RocCli, EachRowCountsTheWindowsOwsimPdCountsOverItsMembers) {
  const TempDir work("owsim_roc_pd");
  write_sweep(work / "sweep", all_members());
  for (const auto& [arguments, pd_arguments] :
       std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>>{
           {{}, {"--bins", "700:800:100"}},
           {{"--target", "wire/1", "--returns", "2", "--range", "680:780"},
            {"--target", "wire/1", "--returns", "2", "--bins", "680:780:100"}}}) {
    std::vector<std::string> command = {"roc", "sweep", "--out", "roc", "--quiet"};
    command.insert(command.end(), arguments.begin(), arguments.end());
    const auto roc = run_cli(command, work.path());
    ASSERT_EQ(roc.exit_status, 0) << roc.err;
    expect_pd_counts_the_same(work.path(), work / "roc/roc.csv", {{1, 4}, {0, 3}, {6, 7}, {2, 5}},
                              write_sweep, pd_arguments);
  }
}

TEST(RocCli, ARealSweepOverTwoThresholdsAgreesAndShowsInTheReportPage) {
  const TempDir work("owsim_roc_real");
  fs::copy_file(kRocSource / "examples/campaigns/hellas_5mm_approach.yaml",
                work / "hellas_5mm_approach.yaml");
  std::ofstream(work / "sweep.yaml")
      << "base: hellas_5mm_approach.yaml\n"
      << "count: 4\nseed: 5\noutputs: summary,truth\nvary:\n"
      << "  sensor.threshold: {values: [0.005, 0.003]}\n"
      << "  trajectory.waypoints.points[0].n: {uniform: [-200, 200]}\n"
      << "  seed: {member: true}\n";
  const auto sweep = run_cli({"sweep", "sweep.yaml", "--out", "campaign", "--quiet"}, work.path());
  ASSERT_EQ(sweep.exit_status, 0) << sweep.err;
  const auto roc = run_cli(
      {"roc", "campaign", "--target", "wire/1", "--range", "300:600", "--quiet"}, work.path());
  ASSERT_EQ(roc.exit_status, 0) << roc.err;
  EXPECT_NE(oracle(work / "campaign", work / "campaign", "sensor.threshold 300 600 1 1 0.95 wire/1")
                .find("roc oracle: 2 values"),
            std::string::npos);
  const auto rows = csv_rows(work / "campaign/roc.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][0], "0.003");
  EXPECT_EQ(rows[2][0], "0.005");
  for (std::size_t r = 1; r <= 2; ++r) {
    EXPECT_EQ(rows[r][1], "2");
    EXPECT_GT(std::stoi(rows[r][2]), 20) << "windows at 300–600 m";
  }
  // The lower threshold detects at least as many windows over the same kind of approaches.
  EXPECT_GE(std::stod(rows[1][4]), std::stod(rows[2][4]));
  const auto copy_members = [&](const fs::path& part, const std::vector<std::size_t>& members) {
    fs::create_directories(part);
    const auto table = test::read_whole_file(work / "campaign/sweep.csv");
    std::istringstream lines(table);
    std::string line;
    std::getline(lines, line);
    std::ofstream out(part / "sweep.csv");
    out << line << '\n';
    while (std::getline(lines, line)) {
      const std::size_t member = std::stoul(line.substr(0, line.find(',')));
      if (std::find(members.begin(), members.end(), member) == members.end()) continue;
      out << line << '\n';
      fs::copy(work / "campaign" / std::to_string(member), part / std::to_string(member));
    }
  };
  expect_pd_counts_the_same(work.path(), work / "campaign/roc.csv", {{1, 3}, {0, 2}}, copy_members,
                            {"--target", "wire/1", "--bins", "300:600:300"});

  // Written into a member's folder, `owsim view` of it carries the rows to the page.
  const auto into_member = run_cli({"roc", "campaign", "--target", "wire/1", "--range", "300:600",
                                    "--out", "campaign/0", "--quiet"},
                                   work.path());
  ASSERT_EQ(into_member.exit_status, 0) << into_member.err;
  const auto view = run_cli({"view", "campaign/0", "--quiet"}, work.path());
  ASSERT_EQ(view.exit_status, 0) << view.err;
  const std::string html = test::read_whole_file(work / "campaign/0/report.html");
  const std::string open = "id=\"owsim-meta\">";
  const std::size_t begin = html.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = html.find("</script>", begin);
  const nlohmann::json meta =
      nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
  const nlohmann::json written =
      nlohmann::json::parse(test::read_whole_file(work / "campaign/0/roc.json"));
  EXPECT_EQ(meta.at("roc").at("rows"), written.at("rows"));
  EXPECT_EQ(meta.at("roc").at("by"), "sensor.threshold");
}

TEST(RocCli, BadKeysFoldersAndOptionsAreRefusedInOneLineWithNothingWritten) {
  const TempDir work("owsim_roc_errors");
  write_sweep(work / "sweep", all_members());
  const auto refused = [&](std::vector<std::string> arguments, const std::string& starts) {
    arguments.insert(arguments.end(), {"--out", "out"});
    const auto result = run_cli(arguments, work.path());
    EXPECT_NE(result.exit_status, 0) << result.command;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.err.rfind("owsim: " + starts, 0), 0u) << result.err;
    EXPECT_FALSE(fs::exists(work / "out")) << result.command;
    EXPECT_FALSE(fs::exists(work / "sweep/roc.csv")) << result.command;
  };
  refused({"roc", "sweep", "--by", "sensor.mount.pitch_deg"},
          "sweep/sweep.csv: sensor.mount.pitch_deg: the sweep does not vary this key (it varies "
          "sensor.threshold, sensor.receiver.noise, seed)");
  refused({"roc", "sweep", "--by", "frames"}, "sweep/sweep.csv: frames: the sweep does not vary");
  refused({"roc", "sweep/0"}, "sweep/0: not a sweep folder (no sweep.csv)");
  refused({"roc", "nowhere"}, "nowhere: not a sweep folder");
  const std::string range =
      "--range: expected 0 ≤ LO < HI ≤ 1000000 m with HI − LO ≥ 0.001 m, got ";
  refused({"roc", "sweep", "--range", "800:700"}, range + "800:700");
  refused({"roc", "sweep", "--range", "-5:10"}, range + "-5:10");
  refused({"roc", "sweep", "--range", "0:1e308"}, range + "0:1e+308");
  refused({"roc", "sweep", "--range", "700:700.0001"}, range + "700:700.0001");
  refused({"roc", "sweep", "--range", "700"}, "--range: expected LO:HI");
  refused({"roc", "sweep", "--range", "700:800:50"}, "--range: expected LO:HI");
  refused({"roc", "sweep", "--range", "nan:800"}, "--range: expected 0 ≤ LO < HI");
  refused({"roc", "sweep", "--confidence", "1.5"}, "--confidence");
  refused({"roc", "sweep", "--window-s", "0"}, "--window-s");
  refused({"roc", "sweep", "--returns", "0"}, "--returns");
  refused({"roc", "sweep", "--class", "cloud"}, "--class: unknown class 'cloud'");
  refused({"roc", "sweep", "--target", "wire/9"}, "--target: no object 'wire/9'");
  refused({"roc", "sweep", "--target", "wire/1", "--class", "wire"}, "--target excludes --class");
  // The three files are all written before any is renamed: one that cannot be leaves none.
  fs::create_directories(work / "half/roc.json.partial");
  const auto half = run_cli({"roc", "sweep", "--out", "half"}, work.path());
  EXPECT_NE(half.exit_status, 0);
  EXPECT_EQ(half.err.rfind("owsim: half/roc.json", 0), 0u) << half.err;
  EXPECT_FALSE(fs::exists(work / "half/roc.csv"));
  EXPECT_FALSE(fs::exists(work / "half/roc.csv.partial"));
  EXPECT_FALSE(fs::exists(work / "half/roc.svg"));
  // The last file cannot be replaced (a folder at its name): the earlier ones keep their bytes.
  const auto whole = run_cli({"roc", "sweep", "--out", "kept", "--quiet"}, work.path());
  ASSERT_EQ(whole.exit_status, 0) << whole.err;
  const std::string kept_csv = test::read_whole_file(work / "kept/roc.csv");
  const std::string kept_json = test::read_whole_file(work / "kept/roc.json");
  fs::remove(work / "kept/roc.svg");
  fs::create_directories(work / "kept/roc.svg/inside");
  const auto blocked =
      run_cli({"roc", "sweep", "--out", "kept", "--range", "600:900"}, work.path());
  EXPECT_NE(blocked.exit_status, 0);
  EXPECT_EQ(blocked.err, "owsim: kept/roc.svg: is a folder: cannot replace it with the report\n");
  EXPECT_EQ(test::read_whole_file(work / "kept/roc.csv"), kept_csv);
  EXPECT_EQ(test::read_whole_file(work / "kept/roc.json"), kept_json);
  EXPECT_FALSE(fs::exists(work / "kept/roc.csv.partial"));
  // A member's files, each named with its line (or key) when it is broken.
  fs::remove(work / "sweep/3/summary.json");
  refused({"roc", "sweep"}, (fs::path("sweep") / "3" / "summary.json").string());
  std::ofstream(work / "sweep/3/summary.json")
      << R"({"frames": 20, "frame_period_s": 1e-300, "pulses": 20000, "returns": {}})";
  refused({"roc", "sweep"},
          "sweep/3/summary.json: frame_period_s: must be a number in [1e-06, 10000000] s, got "
          "1e-300");
  write_member(work / "sweep/3", kMembers[3]);
  std::ofstream(work / "sweep/4/truth.csv", std::ios::app)
      << "20,5.125,wire/1,wire,700,0,0,1,1,0,\n";
  refused({"roc", "sweep"},
          "sweep/4/truth.csv:42: frame: must be a whole number in [0, 19] (summary.json counts 20 "
          "frames), got '20'");
  write_member(work / "sweep/4", kMembers[4]);
  std::ofstream(work / "sweep/5/truth.csv", std::ios::app) << "1,2,wire/1\n";
  refused({"roc", "sweep"}, "sweep/5/truth.csv:42");
  write_member(work / "sweep/5", kMembers[5]);
  std::ofstream(work / "sweep/sweep.csv") << "frames,pulses\n";
  refused({"roc", "sweep"}, "sweep/sweep.csv:1");
}

}  // namespace
}  // namespace owsim
