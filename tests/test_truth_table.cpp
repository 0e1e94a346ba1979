// Protects the readers of a run folder for `owsim pd`, `roc` and `score`
// (evaluation/truth_table.hpp, evaluation/flight_facts.hpp): a run folder is data (issue 45), so
// every summary.json value and every truth.csv cell is checked against what a run writes — NaN,
// infinite and 1e308 ranges, negative frames, frames of ±9·10¹⁸ or past summary.json's count, a
// frame period of 1e-300, negative or fractional counts, unknown classes, an object changing class
// — and refused in one line naming the file, the line and the column (or the key); rows a run
// writes (ids with quotes and line breaks, a byte-order mark, rows across the file reader's blocks)
// read back exactly; sweep.csv lists each member once, in increasing order.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "evaluation/truth_table.hpp"
#include "geometry/error.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

const std::string kHeader =
    "frame,time_s,object,class,range_m,alpha_deg,beta_deg,in_view,returns,closing_speed_mps,"
    "time_to_reach_s\n";

const FlightFacts kSixFrames{6, 1.0 / 3.0, 122112, 9};

bool every_object(std::string_view, std::string_view) { return true; }

std::string summary_error(const std::string& text) {
  try {
    (void)parse_flight_facts(text, "s.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string truth_error(const std::string& rows, const FlightFacts& facts = kSixFrames) {
  try {
    (void)parse_truth_csv(kHeader + rows, "t.csv", facts, every_object);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FlightFacts, ReadsTheKeysOfARunsSummary) {
  // Keys in any order; the same names inside other values (the objects) are not the run's.
  const FlightFacts facts = parse_flight_facts(
      R"({"objects": [{"frames": 99, "pulses": 5}], "frames": 6, "frame_period_s": 0.25,
          "pulses": 122112, "returns": {"wire": 227, "noise": 9}, "seed": 42})",
      "s.json");
  EXPECT_EQ(facts.frames, 6);
  EXPECT_EQ(facts.frame_period_s, 0.25);
  EXPECT_EQ(facts.pulses, 122112u);
  EXPECT_EQ(facts.noise_returns, 9u);
  EXPECT_DOUBLE_EQ(facts.flight_s(), 1.5);
  // A summary from before the receiver counted noise: none.
  EXPECT_EQ(parse_flight_facts(
                R"({"frames": 1, "frame_period_s": 1e-6, "pulses": 0, "returns": {}})", "s.json")
                .noise_returns,
            0u);
}

TEST(FlightFacts, ValuesNoRunWritesAreRefusedNamingTheKey) {
  const auto with = [](const std::string& frames, const std::string& period,
                       const std::string& pulses, const std::string& returns) {
    return summary_error("{\"frames\": " + frames + ", \"frame_period_s\": " + period +
                         ", \"pulses\": " + pulses + ", \"returns\": " + returns + "}");
  };
  const std::string ok_returns = R"({"noise": 3})";
  EXPECT_EQ(with("6", "0.25", "100", ok_returns), "");
  EXPECT_EQ(with("6", "1e-300", "100", ok_returns),
            "s.json: frame_period_s: must be a number in [1e-06, 10000000] s, got 1e-300");
  EXPECT_EQ(with("6", "-0.25", "100", ok_returns),
            "s.json: frame_period_s: must be a number in [1e-06, 10000000] s, got -0.25");
  EXPECT_EQ(with("6", "1e308", "100", ok_returns),
            "s.json: frame_period_s: must be a number in [1e-06, 10000000] s, got 1e+308");
  EXPECT_EQ(with("6", "\"0.25\"", "100", ok_returns),
            "s.json: frame_period_s: must be a number in [1e-06, 10000000] s, got \"0.25\"");
  EXPECT_EQ(with("0", "0.25", "100", ok_returns),
            "s.json: frames: must be a whole number in [1, 1000000000000], got 0");
  EXPECT_EQ(with("-3", "0.25", "100", ok_returns),
            "s.json: frames: must be a whole number in [1, 1000000000000], got -3");
  EXPECT_EQ(with("6.5", "0.25", "100", ok_returns),
            "s.json: frames: must be a whole number in [1, 1000000000000], got 6.5");
  EXPECT_EQ(with("9000000000000000000", "0.25", "100", ok_returns),
            "s.json: frames: must be a whole number in [1, 1000000000000], got "
            "9000000000000000000");
  EXPECT_EQ(with("6", "0.25", "-1", ok_returns),
            "s.json: pulses: must be a whole number in [0, 6291456], got -1");
  EXPECT_EQ(with("6", "0.25", "6291457", ok_returns),  // more than 2^20 pulses a frame
            "s.json: pulses: must be a whole number in [0, 6291456], got 6291457");
  EXPECT_EQ(with("6", "0.25", "100", R"({"noise": 201})"),  // two returns a pulse at most
            "s.json: returns.noise: must be a whole number in [0, 200], got 201");
  EXPECT_EQ(with("6", "0.25", "100", R"({"noise": 1.5})"),
            "s.json: returns.noise: must be a whole number in [0, 200], got 1.5");
  EXPECT_EQ(with("6", "0.25", "100", "[1]"),
            "s.json: returns: must be an object of counts by class, got [1]");
  EXPECT_EQ(summary_error(R"({"frames": 6, "pulses": 1, "returns": {}})"),
            "s.json: no frame_period_s (written by an owsim before 0.2: run the flight again)");
  EXPECT_EQ(summary_error(R"({"frame_period_s": 1, "pulses": 1, "returns": {}})"),
            "s.json: not an owsim summary: no frames");
  EXPECT_EQ(summary_error("[6]"), "s.json: not an owsim summary: not a JSON object");
  EXPECT_EQ(summary_error("{\"frames\": 6,").rfind("s.json: not an owsim summary: ", 0), 0u);
  // A long value is cut in the message, which stays one line.
  const std::string long_period = "\"" + std::string(100, 'x') + "\\n\"";
  const std::string message = with("6", long_period, "100", ok_returns);
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_LT(message.size(), 140u);
}

TEST(TruthTable, ReadsTheRowsARunWrites) {
  const std::string rows =
      "0,0.166516666,line-a/1,wire,594.686,0.1379,-0.0026,1,20,39.909,14.901\n"
      "0,0.166516666,\"odd \"\"id\"\",\nwith a break\",pole,626.609,1.0417,18.6027,0,0,-1.000,\n"
      "1,0.499549999,line-a/1,wire,581.396,0.0497,-0.0024,1,16,0.000,\n"
      "5,1.831,line-a/1,wire,0,-90,180,0,2097152,0.000,1e9\n";
  const std::vector<ObjectTrack> tracks =
      parse_truth_csv("\xEF\xBB\xBF" + kHeader + rows, "t.csv", kSixFrames, every_object);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[0].id, "line-a/1");
  EXPECT_EQ(tracks[0].object_class, "wire");
  ASSERT_EQ(tracks[0].rows.size(), 3u);
  EXPECT_EQ(tracks[0].rows[1].frame, 1);
  EXPECT_DOUBLE_EQ(tracks[0].rows[1].range_m, 581.396);
  EXPECT_EQ(tracks[0].rows[1].returns, 16u);
  EXPECT_EQ(tracks[0].rows[2].frame, 5);
  EXPECT_EQ(tracks[0].rows[2].returns, 2097152u);  // both returns of 2^20 pulses
  EXPECT_EQ(tracks[1].id, "odd \"id\",\nwith a break");
  EXPECT_EQ(tracks[1].object_class, "pole");
  ASSERT_EQ(tracks[1].rows.size(), 1u);
  EXPECT_DOUBLE_EQ(tracks[1].rows[0].closing_speed_mps, -1.0);
  // After the quoted line break, lines are still counted in the file's lines.
  EXPECT_EQ(truth_error("0,0.1,a,wire,1,0,0,1,0,0,\n"
                        "0,0.1,\"b\nc\",wire,1,0,0,1,0,0,\n"
                        "0,0.1,d,wire,nan,0,0,1,0,0,\n"),
            "t.csv:5: range_m: must be a number in [0, 1000000] m, got 'nan'");
}

TEST(TruthTable, CellsNoRunWritesAreRefusedNamingLineAndColumn) {
  const auto row = [](const std::string& frame, const std::string& range,
                      const std::string& tail = "0,0,1,1,0,") {
    return frame + ",0.5,wire/1,wire," + range + "," + tail + "\n";
  };
  const std::string range_error = "t.csv:2: range_m: must be a number in [0, 1000000] m, got ";
  EXPECT_EQ(truth_error(row("0", "600")), "");
  EXPECT_EQ(truth_error(row("0", "nan")), range_error + "'nan'");
  EXPECT_EQ(truth_error(row("0", "inf")), range_error + "'inf'");
  EXPECT_EQ(truth_error(row("0", "-inf")), range_error + "'-inf'");
  EXPECT_EQ(truth_error(row("0", "1e308")), range_error + "'1e308'");
  EXPECT_EQ(truth_error(row("0", "-0.5")), range_error + "'-0.5'");
  EXPECT_EQ(truth_error(row("0", "")), range_error + "''");
  const std::string frame_error =
      "t.csv:2: frame: must be a whole number in [0, 5] (summary.json counts 6 frames), got ";
  EXPECT_EQ(truth_error(row("-1", "600")), frame_error + "'-1'");
  EXPECT_EQ(truth_error(row("6", "600")), frame_error + "'6'");  // past summary.json's frames
  EXPECT_EQ(truth_error(row("9000000000000000000", "600")), frame_error + "'9000000000000000000'");
  EXPECT_EQ(truth_error(row("-9000000000000000000", "600")),
            frame_error + "'-9000000000000000000'");
  EXPECT_EQ(truth_error(row("99999999999999999999999", "600")),
            frame_error + "'99999999999999999999999'");
  EXPECT_EQ(truth_error(row("1.5", "600")), frame_error + "'1.5'");
  EXPECT_EQ(truth_error("0,nan,wire/1,wire,600,0,0,1,1,0,\n"),
            "t.csv:2: time_s: must be a finite number, got 'nan'");
  EXPECT_EQ(truth_error("0,0.5,wire/1,cloud,600,0,0,1,1,0,\n"),
            "t.csv:2: class: must be building, pole, tree or wire, got 'cloud'");
  EXPECT_EQ(truth_error(row("0", "600", "90.5,0,1,1,0,")),
            "t.csv:2: alpha_deg: must be a number in [-90, 90]°, got '90.5'");
  EXPECT_EQ(truth_error(row("0", "600", "0,-inf,1,1,0,")),
            "t.csv:2: beta_deg: must be a number in [-180, 180]°, got '-inf'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,2,1,0,")),
            "t.csv:2: in_view: must be 0 or 1, got '2'");
  const std::string returns_error =
      "t.csv:2: returns: must be a whole number in [0, 2097152], got ";
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,-1,0,")), returns_error + "'-1'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,1.5,0,")), returns_error + "'1.5'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,2097153,0,")), returns_error + "'2097153'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,18446744073709551615,0,")),
            returns_error + "'18446744073709551615'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,1,inf,")),
            "t.csv:2: closing_speed_mps: must be a finite number, got 'inf'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,1,40,")),
            "t.csv:2: time_to_reach_s: empty, though the aircraft closes, got ''");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,1,-40,15")),
            "t.csv:2: time_to_reach_s: given, though the aircraft opens the range, got '15'");
  EXPECT_EQ(truth_error(row("0", "600", "0,0,1,1,40,-15")),
            "t.csv:2: time_to_reach_s: must be a number in [0, ∞) s, got '-15'");
  EXPECT_EQ(truth_error("0,0.5,,wire,600,0,0,1,1,0,\n"),
            "t.csv:2: object: must not be empty, got ''");
  EXPECT_EQ(truth_error("0,0.5,a\xC0,wire,600,0,0,1,1,0,\n"),
            "t.csv:2: object: must be UTF-8 text, got 'a\xC0'");
  EXPECT_EQ(truth_error("0,0.5,w,wire,600,0,0,1,1,0,\n1,0.5,w,pole,600,0,0,1,1,0,\n"),
            "t.csv:3: class: object 'w' is a wire on an earlier row, got 'pole'");
  EXPECT_EQ(truth_error("1,0.5,w,wire,600,0,0,1,1,0,\n1,0.5,w,wire,600,0,0,1,1,0,\n"),
            "t.csv:3: frame 1 of 'w' after frame 1");
  EXPECT_EQ(truth_error("0,0.5,w,wire,600\n"), "t.csv:2: 5 cells, expected 11");
  // Objects not asked for are checked all the same.
  try {
    (void)parse_truth_csv(kHeader + row("0", "inf"), "t.csv", kSixFrames,
                          [](std::string_view, std::string_view) { return false; });
    ADD_FAILURE() << "an infinite range of an object not asked for was read";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), range_error + "'inf'");
  }
  // A cell shown in a message is cut and its control characters replaced: one line.
  const std::string message = truth_error(row("0", "\"1\n" + std::string(200, '9') + "\""));
  EXPECT_EQ(message, range_error + "'\"1?" + std::string(37, '9') + "…'");
  EXPECT_EQ(truth_error(""), "");
  EXPECT_EQ(truth_error("\n\n"), "");
}

TEST(TruthTable, TheFileIsReadInBlocksAndARowHasABoundedLength) {
  const test::TempDir work("owsim_truth_table");
  // 60,000 rows (over 2 MB): rows across the reader's 1 MiB blocks read whole.
  const FlightFacts facts{60'000, 0.1, 0, 0};
  {
    std::ofstream truth(work / "truth.csv", std::ios::binary);
    truth << kHeader;
    for (int f = 0; f < 60'000; ++f) {
      truth << f << "," << f * 0.1 << ",\"wire,"
            << "long/1\",wire," << 1000 - f * 0.01 << ",0.1234,-5.4321,1," << f % 3
            << ",12.345,5\n";
    }
  }
  const std::vector<ObjectTrack> tracks = read_truth_csv(work / "truth.csv", facts, every_object);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0].id, "wire,long/1");
  ASSERT_EQ(tracks[0].rows.size(), 60'000u);
  std::uint64_t returns = 0;
  for (std::size_t i = 0; i < tracks[0].rows.size(); ++i) {
    ASSERT_EQ(tracks[0].rows[i].frame, static_cast<std::int64_t>(i));
    returns += tracks[0].rows[i].returns;
  }
  EXPECT_EQ(returns, 60'000u);  // 0 + 1 + 2 every three frames
  // A row longer than any a run writes (an id of a 16 MiB scenario, quotes doubled) is refused
  // before it is held whole, however the file goes on.
  {
    std::ofstream truth(work / "truth.csv", std::ios::binary);
    truth << kHeader << "0,0.5,w,wire,600,0,0,1,1,0,\n0,0.5,\"";
    const std::string block(1 << 20, 'x');
    for (int i = 0; i < 40; ++i) truth << block;
  }
  try {
    (void)read_truth_csv(work / "truth.csv", facts, every_object);
    ADD_FAILURE() << "a 40 MiB row was read";
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()),
        (work / "truth.csv").string() + ":3: a row longer than 33558528 bytes (no run writes one)");
  }
}

TEST(TruthTable, ASweepTableListsEachMemberOnceInIncreasingOrder) {
  const test::TempDir work("owsim_sweep_members");
  const auto error_of = [&](const std::string& table) {
    std::ofstream(work / "sweep.csv") << table;
    try {
      (void)campaign_flights(work.path());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string where = (work / "sweep.csv").string();
  EXPECT_EQ(error_of("member,seed\n0,1\n1,2\n"), "");
  EXPECT_EQ(error_of("member,seed\n1,1\n4,2\n"), "");  // a part of a sweep, as tests copy it
  EXPECT_EQ(error_of("member,seed\n0,1\n0,1\n"),
            where + ":3: member 0 after member 0 (each member once, in order)");
  EXPECT_EQ(error_of("member,seed\n0,1\n2,1\n1,1\n"),
            where + ":4: member 1 after member 2 (each member once, in order)");
  EXPECT_EQ(error_of("member,seed\n-1,1\n"), where + ":2: member '-1' is not a member number");
  std::ofstream(work / "sweep.csv")
      << "member,seed\n0,1\n1,1\n2,1\n3,1\n4,1\n5,1\n6,1\n7,1\n8,1\n9,1\n10,1\n";
  const std::vector<CampaignFlight> members = campaign_flights(work.path());
  ASSERT_EQ(members.size(), 11u);
  EXPECT_EQ(members[3].name, "03");
  EXPECT_EQ(members[10].directory, work.path() / "10");
}

}  // namespace
}  // namespace owsim
