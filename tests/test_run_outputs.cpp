// Protects what `owsim run` writes, end to end through the built CLI (INTERFACE.md "owsim run
// outputs", SENSOR-SPEC §2, §5, §8): the d64 words (count, FG/LG, time tags, reserved bits,
// encoder direction, reference fiber), points.csv rows against the returns in the words, ground
// points on flat terrain to 1 mm and wire points within the capture distance of the analytic
// catenary with noise off, lat/lon/h against e/n/u through pyproj, byte-identical outputs with 1
// and 2 threads, and a heading through north without a spurious turn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/run/output_kind.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/trajectory/hellsim_reader.hpp"
#include "python_oracle.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

// The sensor's constants as SENSOR-SPEC states them, not as the library computes them.
constexpr int kPulsesPerFrame = 20'352;  // §2: 159 lines × 128 fibers
constexpr int kFibersPerLine = 128;
constexpr double kPrfHz = 61'111.0;                                // §1
constexpr double kCountM = 299'792'500.0 * 4e-9 / (2.0 * 1.0003);  // §1 eq 3.2: Δ
constexpr unsigned kTimeout = 2066;                                // §1 eq 9.4
constexpr unsigned kReferenceCounts = 10;                          // §8
constexpr double kTimeTagS = 100e-6;                               // §8 eq 10.1

constexpr const char* kPointsHeader =
    "frame,pulse,line,fiber,return,time_s,range_m,counter,e_m,n_m,u_m,lat_deg,lon_deg,h_m,class,"
    "object,energy_rel,incidence_deg";
constexpr const char* kTrajectoryHeader =
    "time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg";

fs::path example(const std::string& name) {
  return fs::path(OWSIM_SOURCE_DIR) / "examples" / (name + ".yaml");
}

// ---- reading the outputs, independently of the writers ----

std::vector<std::uint64_t> read_words(const fs::path& path) {
  const std::string bytes = test::read_whole_file(path);
  std::vector<std::uint64_t> words(bytes.size() / 8);
  for (std::size_t i = 0; i < words.size(); ++i) {
    std::uint64_t word = 0;
    for (int b = 7; b >= 0; --b) {
      word = (word << 8) | static_cast<unsigned char>(bytes[8 * i + static_cast<std::size_t>(b)]);
    }
    words[i] = word;
  }
  return words;
}

unsigned counter1(std::uint64_t w) { return static_cast<unsigned>(w & 0xFFFu); }
unsigned counter2(std::uint64_t w) { return static_cast<unsigned>((w >> 16) & 0xFFFu); }
bool frame_gate(std::uint64_t w) { return ((w >> 31) & 1u) != 0; }
bool line_gate(std::uint64_t w) { return ((w >> 30) & 1u) != 0; }
int encoder(std::uint64_t w) { return static_cast<std::int16_t>((w >> 32) & 0xFFFFu); }
unsigned time_tag(std::uint64_t w) { return static_cast<unsigned>(w >> 48); }

// A CSV file as rows of cells (no quoted cells in these scenarios' ids), with its header.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::map<std::string, std::size_t> column;

  [[nodiscard]] const std::string& at(std::size_t row, const std::string& name) const {
    return rows[row][column.at(name)];
  }
  [[nodiscard]] double number(std::size_t row, const std::string& name) const {
    return std::stod(at(row, name));
  }
  [[nodiscard]] long long integer(std::size_t row, const std::string& name) const {
    return std::stoll(at(row, name));
  }
};

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream stream(line);
  while (std::getline(stream, cell, separator)) cells.push_back(cell);
  if (!line.empty() && line.back() == separator) cells.emplace_back();
  return cells;
}

Csv read_csv(const fs::path& path, std::string& header_line) {
  Csv csv;
  std::ifstream file(path);
  std::getline(file, header_line);
  csv.header = split(header_line, ',');
  for (std::size_t i = 0; i < csv.header.size(); ++i) csv.column[csv.header[i]] = i;
  std::string line;
  while (std::getline(file, line)) csv.rows.push_back(split(line, ','));
  return csv;
}

// ---- the runs the tests share (each made once, on first use) ----

class OwsimRun {
 public:
  OwsimRun(const fs::path& scenario, std::vector<std::string> options) : dir_("owsim_run_outputs") {
    std::vector<std::string> arguments = {"run", scenario.string(), "--out", out().string(),
                                          "--quiet"};
    arguments.insert(arguments.end(), options.begin(), options.end());
    result_ = run_cli(arguments, dir_.path());
  }
  [[nodiscard]] fs::path out() const { return dir_ / "out"; }
  [[nodiscard]] const CliResult& result() const { return result_; }
  [[nodiscard]] const TempDir& dir() const { return dir_; }

 private:
  TempDir dir_;
  CliResult result_;
};

constexpr int kPylonFrames = 12;  // the line-s conductors are in view from frame 0

// pylon_line with noise off: the geometric checks.
const OwsimRun& pylon_line_no_noise() {
  static const OwsimRun run(example("pylon_line"), {"--frames", std::to_string(kPylonFrames),
                                                    "--no-noise", "--threads", "2"});
  return run;
}

// single_span starting at 6.4 s on the trajectory's clock: the time tags wrap at 6.5536 s.
constexpr double kShiftedStartS = 6.4;
const OwsimRun& single_span_shifted() {
  struct Shifted {
    TempDir dir{"owsim_shifted_scenario"};
    fs::path path = dir / "single_span_shifted.yaml";
    Shifted() {
      std::string text = test::read_whole_file(example("single_span"));
      const std::string from = "start_s: 0\n";
      const std::size_t at = text.find(from);
      if (at != std::string::npos) text.replace(at, from.size(), "start_s: 6.4\n");
      std::ofstream(path) << text;
    }
  };
  static const Shifted scenario;
  static const OwsimRun run(scenario.path, {"--frames", "2", "--outputs", "d64,points,trajectory"});
  return run;
}

constexpr int kCorridorFrames = 6;
const OwsimRun& corridor_threads(int threads) {
  static const OwsimRun one(example("corridor"),
                            {"--frames", std::to_string(kCorridorFrames), "--threads", "1"});
  static const OwsimRun two(example("corridor"),
                            {"--frames", std::to_string(kCorridorFrames), "--threads", "2"});
  return threads == 1 ? one : two;
}

// ---- words ----

void expect_words_of_the_spec(const OwsimRun& run, int frames, double start_s, bool noise_free) {
  ASSERT_EQ(run.result().exit_status, 0) << run.result().command << "\n" << run.result().err;
  const std::vector<std::uint64_t> words = read_words(run.out() / "flight.d64");
  ASSERT_EQ(fs::file_size(run.out() / "flight.d64"),
            static_cast<std::uintmax_t>(frames) * kPulsesPerFrame * 8);
  ASSERT_EQ(words.size(), static_cast<std::size_t>(frames) * kPulsesPerFrame);

  std::size_t tag_wraps = 0;
  for (std::size_t n = 0; n < words.size(); ++n) {
    const std::uint64_t w = words[n];
    ASSERT_EQ(frame_gate(w), (n + 1) % kPulsesPerFrame == 0) << "word " << n;
    ASSERT_EQ(line_gate(w), (n + 1) % kFibersPerLine == 0) << "word " << n;
    ASSERT_EQ(w & 0x3000F000u, 0u) << "crosstalk, reserved, LUT and trigger bits of word " << n;

    // time tag = floor(t / 100 µs) mod 65536, t = start_s + n / PRF (§2, §8); a t within 1e-6
    // tick of a tick boundary may fall either side in double arithmetic.
    const long double ticks = (static_cast<long double>(start_s) +
                               static_cast<long double>(n) / static_cast<long double>(kPrfHz)) /
                              static_cast<long double>(kTimeTagS);
    const auto low = static_cast<long long>(std::floor(ticks - 1e-6L)) % 65'536;
    const auto high = static_cast<long long>(std::floor(ticks + 1e-6L)) % 65'536;
    ASSERT_TRUE(time_tag(w) == low || time_tag(w) == high)
        << "word " << n << ": tag " << time_tag(w) << ", expected " << high;
    if (n > 0 && time_tag(w) < time_tag(words[n - 1])) ++tag_wraps;

    ASSERT_LE(counter1(w), kTimeout) << "word " << n;
    ASSERT_LE(counter2(w), kTimeout) << "word " << n;
    if (counter1(w) == kTimeout) {
      ASSERT_EQ(counter2(w), kTimeout) << "word " << n << ": a second return without a first";
    }
    if ((n + 1) % kFibersPerLine == 0) {  // the reference fiber: the internal range, one return
      ASSERT_EQ(counter2(w), kTimeout) << "word " << n;
      if (noise_free) {
        ASSERT_EQ(counter1(w), kReferenceCounts) << "word " << n;
      } else {
        ASSERT_NEAR(counter1(w), kReferenceCounts, 4.0) << "word " << n;  // σ = 0.71 counts
      }
    }
  }
  const double end_s = start_s + static_cast<double>(words.size()) / kPrfHz;
  EXPECT_EQ(tag_wraps, static_cast<std::size_t>(std::floor(end_s / (65'536 * kTimeTagS))) -
                           static_cast<std::size_t>(std::floor(start_s / (65'536 * kTimeTagS))));

  // The mirror sweeps up on even frames and down on odd ones (§2), and the encoder φ(β) falls
  // as β rises (§3): the encoder falls through an even frame and rises through an odd one.
  for (int f = 0; f < frames; ++f) {
    const std::size_t first = static_cast<std::size_t>(f) * kPulsesPerFrame;
    const int direction = f % 2 == 0 ? -1 : 1;
    for (std::size_t k = 1; k < kPulsesPerFrame; ++k) {
      ASSERT_GE(direction * (encoder(words[first + k]) - encoder(words[first + k - 1])), 0)
          << "frame " << f << " pulse " << k;
    }
    EXPECT_GT(std::abs(encoder(words[first + kPulsesPerFrame - 1]) - encoder(words[first])), 5000)
        << "frame " << f << ": a 36° sweep spans ~5,100 encoder counts";
  }
}

TEST(RunOutputs, WordsCarryGatesTimeTagsAndTheReferenceFiber) {
  expect_words_of_the_spec(pylon_line_no_noise(), kPylonFrames, 0.0, true);
}

TEST(RunOutputs, TimeTagsFollowTheTrajectoryClockAndWrap) {
  const OwsimRun& run = single_span_shifted();
  expect_words_of_the_spec(run, 2, kShiftedStartS, false);
  const std::vector<std::uint64_t> words = read_words(run.out() / "flight.d64");
  ASSERT_FALSE(words.empty());
  EXPECT_EQ(time_tag(words.front()), 64'000u);  // floor(6.4 s / 100 µs)
  std::string header;
  const Csv trajectory = read_csv(run.out() / "trajectory.csv", header);
  ASSERT_EQ(trajectory.rows.size(), 2u);
  EXPECT_NEAR(trajectory.number(0, "time_s"), kShiftedStartS, 1e-9);
  EXPECT_NEAR(trajectory.number(1, "time_s"), kShiftedStartS + kPulsesPerFrame / kPrfHz, 1e-9);
}

TEST(RunOutputs, WordsFromCorridorWithNoise) {
  expect_words_of_the_spec(corridor_threads(2), kCorridorFrames, 0.0, false);
}

// ---- points.csv ↔ words ----

// Every return in the words (counter < timeout on a fiber pulse) is one points.csv row with the
// same counter — return 1 ↔ counter 1, return 2 ↔ counter 2 — and there is no other row.
void expect_rows_are_the_words_returns(const OwsimRun& run, int frames, double start_s) {
  ASSERT_EQ(run.result().exit_status, 0) << run.result().command << "\n" << run.result().err;
  const std::vector<std::uint64_t> words = read_words(run.out() / "flight.d64");
  ASSERT_EQ(words.size(), static_cast<std::size_t>(frames) * kPulsesPerFrame);
  std::string header;
  const Csv points = read_csv(run.out() / "points.csv", header);
  ASSERT_EQ(header, kPointsHeader);

  std::map<std::pair<std::size_t, int>, unsigned> rows;  // (word index, return) → counter
  std::size_t second_returns = 0;
  for (std::size_t r = 0; r < points.rows.size(); ++r) {
    ASSERT_EQ(points.rows[r].size(), points.header.size()) << "row " << r;
    const long long frame = points.integer(r, "frame");
    const long long pulse = points.integer(r, "pulse");
    const int ret = static_cast<int>(points.integer(r, "return"));
    ASSERT_TRUE(frame >= 0 && frame < frames) << "row " << r;
    ASSERT_TRUE(pulse >= 0 && pulse < kPulsesPerFrame) << "row " << r;
    ASSERT_TRUE(ret == 1 || ret == 2) << "row " << r;
    ASSERT_EQ(points.integer(r, "line"), pulse / kFibersPerLine) << "row " << r;
    const long long fiber = points.integer(r, "fiber");
    ASSERT_TRUE(fiber >= 1 && fiber <= 127) << "row " << r << ": the reference fiber has no point";
    ASSERT_NE(pulse % kFibersPerLine, kFibersPerLine - 1) << "row " << r;
    const double t = start_s + static_cast<double>(frame * kPulsesPerFrame + pulse) / kPrfHz;
    ASSERT_NEAR(points.number(r, "time_s"), t, 1e-9) << "row " << r;
    const auto counter = static_cast<unsigned>(points.integer(r, "counter"));
    ASSERT_LT(counter, kTimeout) << "row " << r;
    // counter = round(range / Δ) (§1 decision); range_m is printed to 0.1 mm
    ASSERT_LE(std::abs(points.number(r, "range_m") / kCountM - counter), 0.5 + 1e-4 / kCountM)
        << "row " << r;
    const std::size_t word = static_cast<std::size_t>(frame * kPulsesPerFrame + pulse);
    ASSERT_TRUE(rows.emplace(std::pair{word, ret}, counter).second)
        << "row " << r << " repeats frame " << frame << " pulse " << pulse << " return " << ret;
    if (ret == 2) ++second_returns;
  }

  std::size_t returns_in_words = 0;
  for (std::size_t n = 0; n < words.size(); ++n) {
    if ((n + 1) % kFibersPerLine == 0) continue;  // the reference fiber
    for (int ret = 1; ret <= 2; ++ret) {
      const unsigned counter = ret == 1 ? counter1(words[n]) : counter2(words[n]);
      const auto row = rows.find({n, ret});
      if (counter >= kTimeout) {
        ASSERT_TRUE(row == rows.end()) << "word " << n << " has no return " << ret;
        continue;
      }
      ++returns_in_words;
      ASSERT_TRUE(row != rows.end()) << "word " << n << " return " << ret << " has no row";
      ASSERT_EQ(row->second, counter) << "word " << n << " return " << ret;
    }
  }
  EXPECT_EQ(returns_in_words, points.rows.size());
  EXPECT_GT(points.rows.size(), 1000u);
  EXPECT_GT(second_returns, 0u) << "the scenario should produce second returns";
}

TEST(RunOutputs, PointRowsAreTheWordsReturnsWithoutNoise) {
  expect_rows_are_the_words_returns(pylon_line_no_noise(), kPylonFrames, 0.0);
}

TEST(RunOutputs, PointRowsAreTheWordsReturnsWithNoise) {
  expect_rows_are_the_words_returns(corridor_threads(2), kCorridorFrames, 0.0);
}

// ---- geometry, through the Python oracle ----

// The oracle's figures for the no-noise pylon_line run; the span numbers are the scenario's own
// inputs (support heights, lowest point, ends, layout offsets), the catenary is solved in scipy.
const nlohmann::json& pylon_line_figures() {
  static const nlohmann::json figures = [] {
    const OwsimRun& run = pylon_line_no_noise();
    const Scenario scenario = load_scenario(example("pylon_line"));
    nlohmann::json setup;
    setup["points_csv"] = (run.out() / "points.csv").string();
    setup["trajectory_csv"] = (run.out() / "trajectory.csv").string();
    setup["origin"] = {{"lat", scenario.origin.lat_deg},
                       {"lon", scenario.origin.lon_deg},
                       {"h", scenario.origin.h_m}};
    setup["flat_u"] = scenario.scene.terrain.flat_u_m;
    setup["divergence_mrad"] = scenario.receiver.beam.divergence_mrad;
    setup["beam_exit_radius_m"] = scenario.receiver.beam.exit_radius_m;
    nlohmann::json conductors = nlohmann::json::array();
    const double ground = scenario.scene.terrain.flat_u_m;
    for (const SpanSpec& span : scenario.scene.spans) {
      for (std::size_t i = 0; i < span.offsets.size(); ++i) {
        const ConductorOffset& offset = span.offsets[i];
        conductors.push_back({{"id", span.id + "/" + std::to_string(i + 1)},
                              {"from", {span.from_en.x(), span.from_en.y()}},
                              {"to", {span.to_en.x(), span.to_en.y()}},
                              {"support_1_m", ground + span.support_height_1_m + offset.vertical_m},
                              {"support_2_m", ground + span.support_height_2_m + offset.vertical_m},
                              {"lowest_m", ground + span.lowest_point_m + offset.vertical_m},
                              {"lateral_m", offset.lateral_m},
                              {"radius_m", 0.5 * span.conductor_diameter_m}});
      }
    }
    setup["conductors"] = conductors;
    const fs::path path = run.dir() / "oracle_setup.json";
    std::ofstream(path) << setup.dump();
    const std::string output = test::run_python_file(
        fs::path(OWSIM_SOURCE_DIR) / "tests" / "oracles" / "run_outputs_oracle.py",
        {path.string()});
    return nlohmann::json::parse(output, nullptr, /*allow_exceptions=*/false);
  }();
  return figures;
}

TEST(RunOutputs, GroundPointsLieOnFlatTerrainWithoutNoise) {
  const nlohmann::json& figures = pylon_line_figures();
  ASSERT_TRUE(figures.is_object()) << figures.dump();
  EXPECT_GT(figures["ground_rows"].get<int>(), 10'000);
  EXPECT_LE(figures["ground_max_abs_du_m"].get<double>(), 0.001);
}

TEST(RunOutputs, WirePointsLieWithinTheBeamOfTheirCatenary) {
  const nlohmann::json& figures = pylon_line_figures();
  ASSERT_TRUE(figures.is_object()) << figures.dump();
  EXPECT_GT(figures["wire_rows"].get<int>(), 100);
  EXPECT_GE(figures["wire_conductors_hit"].get<int>(), 5) << "of line-s's 7 conductors";
  EXPECT_TRUE(figures["wire_unknown_objects"].empty()) << figures.dump();
  // distance to the curve ≤ r_wire + r_beam(range) + 2 mm (the 1 mm polyline and the CSV's
  // 0.1 mm rounding)
  EXPECT_LE(figures["wire_max_excess_m"].get<double>(), 0.002) << figures.dump();
}

TEST(RunOutputs, GeodeticColumnsAgreeWithPyproj) {
  const nlohmann::json& figures = pylon_line_figures();
  ASSERT_TRUE(figures.is_object()) << figures.dump();
  EXPECT_GT(figures["point_rows"].get<int>(), 10'000);
  EXPECT_EQ(figures["trajectory_rows"].get<int>(), kPylonFrames);
  // lat/lon printed to 1e-9° (≤ 0.11 mm), heights and e/n/u to 0.1 mm
  EXPECT_LE(figures["point_geodetic_max_error_m"].get<double>(), 0.001) << figures.dump();
  EXPECT_LE(figures["trajectory_geodetic_max_error_m"].get<double>(), 0.001) << figures.dump();
}

// ---- determinism ----

std::set<fs::path> files_below(const fs::path& root) {
  std::set<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), root));
  }
  return files;
}

TEST(RunOutputs, SameSeedGivesTheSameBytesWithOneAndTwoThreads) {
  const OwsimRun& one = corridor_threads(1);
  const OwsimRun& two = corridor_threads(2);
  ASSERT_EQ(one.result().exit_status, 0) << one.result().err;
  ASSERT_EQ(two.result().exit_status, 0) << two.result().err;
  const std::set<fs::path> files = files_below(one.out());
  ASSERT_EQ(files, files_below(two.out()));
  for (const char* name : {"flight.d64", "points.csv", "points.las", "points.ply", "trajectory.csv",
                           "summary.json", "quicklook/map.png", "quicklook/frame_000000.png"}) {
    EXPECT_TRUE(files.contains(name)) << name;
  }
  for (const fs::path& file : files) {
    if (file == "summary.json") continue;
    const std::string a = test::read_whole_file(one.out() / file);
    const std::string b = test::read_whole_file(two.out() / file);
    EXPECT_EQ(a.size(), b.size()) << file;
    EXPECT_TRUE(a == b) << file << " differs between 1 and 2 threads";
  }
  nlohmann::json a = nlohmann::json::parse(test::read_whole_file(one.out() / "summary.json"));
  nlohmann::json b = nlohmann::json::parse(test::read_whole_file(two.out() / "summary.json"));
  EXPECT_EQ(a["threads"], 1);
  EXPECT_EQ(b["threads"], 2);
  for (const char* timing : {"setup_s", "wall_s", "pulses_per_s", "realtime_factor", "threads"}) {
    EXPECT_TRUE(a.contains(timing)) << timing;
    a.erase(timing);
    b.erase(timing);
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["frames"], kCorridorFrames);
  EXPECT_EQ(a["pulses"], kCorridorFrames * kPulsesPerFrame);
}

// Each point file on its own (`--outputs csv`, `las`, `ply`) is byte for byte the file `points`
// writes, and comes alone (with scenario.yaml, which every run folder holds).
TEST(RunOutputs, EachPointFormatAloneIsTheFileOfPoints) {
  const OwsimRun& all = corridor_threads(2);
  ASSERT_EQ(all.result().exit_status, 0) << all.result().err;
  for (const auto& [output, file] : {std::pair{"csv", "points.csv"}, std::pair{"las", "points.las"},
                                     std::pair{"ply", "points.ply"}}) {
    SCOPED_TRACE(output);
    const OwsimRun alone(example("corridor"), {"--frames", std::to_string(kCorridorFrames),
                                               "--threads", "2", "--outputs", output});
    ASSERT_EQ(alone.result().exit_status, 0) << alone.result().err;
    EXPECT_EQ(files_below(alone.out()), (std::set<fs::path>{file, "scenario.yaml"}));
    EXPECT_TRUE(test::read_whole_file(alone.out() / file) ==
                test::read_whole_file(all.out() / file));
  }
}

TEST(RunOutputs, OutputListsReadBack) {
  EXPECT_EQ(output_list(parse_output_list("points")), "points");
  EXPECT_EQ(output_list(parse_output_list("ply,csv,las")), "points");
  EXPECT_EQ(output_list(parse_output_list("las,summary")), "las,summary");
  EXPECT_EQ(parse_output_list("d64,points").size(), 4u);
  EXPECT_TRUE(wants_points(parse_output_list("ply")));
  EXPECT_FALSE(wants_points(parse_output_list("d64,summary,quicklook")));
  EXPECT_THROW((void)parse_output_list("las,xyz"), Error);
}

TEST(RunOutputs, AnotherSeedGivesOtherWords) {
  const OwsimRun& reference = corridor_threads(2);
  const OwsimRun other(example("corridor"), {"--frames", "1", "--seed", "99", "--outputs", "d64"});
  ASSERT_EQ(other.result().exit_status, 0) << other.result().err;
  const std::vector<std::uint64_t> a = read_words(reference.out() / "flight.d64");
  const std::vector<std::uint64_t> b = read_words(other.out() / "flight.d64");
  ASSERT_EQ(b.size(), static_cast<std::size_t>(kPulsesPerFrame));
  ASSERT_GE(a.size(), b.size());
  EXPECT_FALSE(std::equal(b.begin(), b.end(), a.begin())) << "--seed must reach the noise";
}

// ---- heading through north ----

const fs::path kHellsimFile =
    fs::path(OWSIM_SOURCE_DIR) / "examples" / "data" / "hellsim_turn_north.txt";

// The largest heading rate between consecutive records of the bundled file, degrees per second,
// each step taken the short way round.
double file_max_turn_rate_deg_per_s(const std::vector<NavRecord>& records) {
  double rate = 0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    const double step =
        wrap_180_deg(records[i].attitude.heading_deg - records[i - 1].attitude.heading_deg);
    rate = std::max(rate, std::abs(step) / (records[i].time_s - records[i - 1].time_s));
  }
  return rate;
}

TEST(RunOutputs, HeadingThroughNorthHasNoSpuriousTurnInTheTrajectoryCsv) {
  const std::vector<NavRecord> records = read_hellsim(kHellsimFile.string());
  const double max_rate = file_max_turn_rate_deg_per_s(records);
  ASSERT_NEAR(max_rate, 3.0, 0.01);

  const OwsimRun run(example("hellsim_flight"), {"--duration", "25", "--outputs", "trajectory"});
  ASSERT_EQ(run.result().exit_status, 0) << run.result().command << "\n" << run.result().err;
  std::string header;
  const Csv trajectory = read_csv(run.out() / "trajectory.csv", header);
  ASSERT_EQ(header, kTrajectoryHeader);
  ASSERT_EQ(trajectory.rows.size(), 75u);  // floor(25 s / 0.33304 s)

  const double frame_s = kPulsesPerFrame / kPrfHz;
  int crossings = 0;
  for (std::size_t r = 1; r < trajectory.rows.size(); ++r) {
    const double before = trajectory.number(r - 1, "heading_deg");
    const double after = trajectory.number(r, "heading_deg");
    ASSERT_TRUE(after >= 0.0 && after < 360.0) << "row " << r;
    if (before > 300.0 && after < 60.0) ++crossings;
    const double step = wrap_180_deg(after - before);  // the unwrapped per-frame change
    ASSERT_GE(step, -0.01) << "row " << r << ": the aircraft only turns right";
    ASSERT_LE(step, max_rate * frame_s * 1.03)
        << "row " << r << ": " << before << "° → " << after << "°";
  }
  EXPECT_EQ(crossings, 1);
  EXPECT_GT(trajectory.number(0, "heading_deg"), 300.0);
  EXPECT_LT(trajectory.number(trajectory.rows.size() - 1, "heading_deg"), 30.0);
}

TEST(RunOutputs, HeadingThroughNorthInterpolatesSmoothlyInTheTrajectory) {
  const Scenario scenario = load_scenario(example("hellsim_flight"));
  const std::vector<NavRecord> records = read_hellsim(kHellsimFile.string());
  ASSERT_EQ(records.size(), 601u);
  EXPECT_NEAR(records.back().time_s, 60.0, 1e-9) << "the Time-Tag wraps once and must unwrap";
  const double max_rate = file_max_turn_rate_deg_per_s(records);

  const LocalFrame frame(scenario.origin);
  TrajectoryOptions options;
  options.smoothing = {scenario.trajectory.smoothing_window, scenario.trajectory.smoothing_degree};
  const Trajectory trajectory(to_local(records, frame), frame, options);
  ASSERT_NEAR(trajectory.end_s(), 60.0, 1e-9);

  // Sampled every 10 ms: every step turns right by at most the file's rate, the rate itself
  // stays within it, and north is crossed once, where the file crosses it (t = 21.5 s).
  constexpr double kStepS = 0.01;
  double previous = trajectory.pose_at(0.0).attitude.heading_deg;
  int crossings = 0;
  double crossing_s = 0;
  for (int i = 1; i * kStepS <= 60.0 + 1e-9; ++i) {
    const double t = i * kStepS;
    const double heading = trajectory.pose_at(t).attitude.heading_deg;
    ASSERT_TRUE(heading >= 0.0 && heading < 360.0) << "t = " << t;
    const double step = wrap_180_deg(heading - previous);
    ASSERT_GE(step, -1e-3) << "t = " << t;
    ASSERT_LE(step, max_rate * kStepS * 1.03)
        << "t = " << t << ": " << previous << "° → " << heading << "°";
    const double rate = trajectory.heading_rate_deg_per_s(t);
    ASSERT_GE(rate, -0.1) << "t = " << t;
    ASSERT_LE(rate, max_rate * 1.03) << "t = " << t;
    if (previous > 300.0 && heading < 60.0) {
      ++crossings;
      crossing_s = t;
    }
    previous = heading;
  }
  EXPECT_EQ(crossings, 1);
  EXPECT_NEAR(crossing_s, 21.5, 0.05);
  // Through the turn the interpolated heading stays on the file's (smoothing a steady turn
  // changes nothing).
  for (std::size_t i = 0; i < records.size(); ++i) {
    const double t = records[i].time_s;
    if (t < 9.0 || t > 44.0) continue;
    EXPECT_NEAR(
        wrap_180_deg(trajectory.pose_at(t).attitude.heading_deg - records[i].attitude.heading_deg),
        0.0, 0.01)
        << "t = " << t;
  }
}

}  // namespace
}  // namespace owsim
