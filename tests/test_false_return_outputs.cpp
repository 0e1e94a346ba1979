// Protects false returns (class noise, SENSOR-SPEC §11; INTERFACE.md "Receiver noise and
// sunlight") in the files `owsim run` writes: frames with known false returns — one alone, one
// before a wire — go through FlightOutputs, and points.csv (class noise, empty object, energy_rel
// = T, empty incidence), points.las (classification 7, low noise), points.ply (class 7), the words
// (the false return's counter) and summary.json (returns.noise, false_returns_per_pulse) are read
// back byte by byte; `owsim view`'s readers take LAS 7 and PLY 7 back to noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/recording/milows_word.hpp"
#include "io/report/report_points.hpp"
#include "io/run/flight_outputs.hpp"
#include "sensor/range_counter.hpp"
#include "synthetic_flight.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

const Geodetic kOrigin{48.6881, 10.8447, 450.0};
constexpr std::int64_t kFrames = 2;
constexpr double kThreshold = 0.0029;  // T: a false return's energy_rel
constexpr std::uint32_t kWire = 1;     // "span/2" of test::small_scene

// Pulses 100 (a false return alone) and 300 (a false return, then wire span/2) of each frame; no
// other returns.
struct KnownReturns {
  std::size_t alone = 100;
  std::size_t before_wire = 300;
};

Return return_at(double range_m, SurfaceClass surface, std::uint32_t object, double energy_rel,
                 double incidence_deg, const RangeCounterParams& counter) {
  Return r;
  r.range_m = range_m;
  r.true_range_m = range_m;
  r.counter = counter_from_range(range_m, counter);
  r.surface = static_cast<std::uint8_t>(surface);
  r.object_index = object;
  r.energy_rel = energy_rel;
  r.incidence_deg = incidence_deg;
  return r;
}

test::SyntheticFrame frame_with_false_returns(const ScanParams& scan, std::int64_t k) {
  test::SyntheticFrame frame = test::synthetic_frame(scan, k);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (PulseReturns& r : frame.returns) {
    r = PulseReturns{};
    r.counter1 = r.counter2 = scan.counter.timeout_counts;
  }
  const KnownReturns at;
  PulseReturns& alone = frame.returns[at.alone];
  alone.count = 1;
  alone.returns[0] =
      return_at(412.5, SurfaceClass::noise, kNoObject, kThreshold, nan, scan.counter);
  alone.counter1 = alone.returns[0].counter;
  PulseReturns& pair = frame.returns[at.before_wire];
  pair.count = 2;
  pair.returns[0] = return_at(97.25, SurfaceClass::noise, kNoObject, kThreshold, nan, scan.counter);
  pair.returns[1] = return_at(240.0, SurfaceClass::wire, kWire, 0.0125, 61.5, scan.counter);
  pair.counter1 = pair.returns[0].counter;
  pair.counter2 = pair.returns[1].counter;
  return frame;
}

std::vector<std::string> text_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string fixed_text(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

template <typename T>
T field(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

class FalseReturnOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    for (std::int64_t k = 0; k < kFrames; ++k)
      frames_.push_back(frame_with_false_returns(scan_, k));
    const KnownReturns at;
    ASSERT_FALSE(frames_[0].pulses[at.alone].reference);  // ranging fibers: their words hold them
    ASSERT_FALSE(frames_[0].pulses[at.before_wire].reference);
    FlightOutputOptions options;
    options.directory = dir_.path() / "run";
    options.outputs = {OutputKind::d64, OutputKind::csv, OutputKind::las, OutputKind::ply,
                       OutputKind::summary};
    FlightOutputs outputs(options, scene_, scan_, local_frame_);
    for (const test::SyntheticFrame& frame : frames_) outputs.add_frame(frame.view(), frame.start);
    outputs.finish({{"scenario", "false returns"}});
    files_ = test::files_under(options.directory);
  }

  const test::TempDir dir_{"owsim_false_returns"};
  ScanParams scan_;
  Scene scene_ = test::small_scene();
  LocalFrame local_frame_{kOrigin};
  std::vector<test::SyntheticFrame> frames_;
  std::map<std::string, std::string> files_;
};

TEST_F(FalseReturnOutputs, PointsCsvRowsSayNoiseWithNoObjectAndNoIncidence) {
  const std::vector<std::string> lines = text_lines(files_.at("points.csv"));
  ASSERT_EQ(lines.size(), 1 + 3 * kFrames);
  const KnownReturns at;
  const test::SyntheticFrame& frame = frames_[1];
  // Frame 1: rows 4 (the lone false return), 5 (the false return first) and 6 (the wire second).
  const struct {
    std::size_t pulse;
    int r;
    std::string tail;  // class, object, energy_rel, incidence_deg
  } expected[] = {{at.alone, 0, "noise,,0.0029,"},
                  {at.before_wire, 0, "noise,,0.0029,"},
                  {at.before_wire, 1, "wire,span/2,0.0125,61.5000"}};
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    const Pulse& pulse = frame.pulses[expected[i].pulse];
    const Return& ret = frame.returns[expected[i].pulse].returns[expected[i].r];
    const PulseRay& ray = frame.rays[expected[i].pulse];
    const Eigen::Vector3d enu = ray.origin_enu_m + ret.range_m * ray.dir_enu;
    const std::string head = "1," + std::to_string(pulse.index) + "," + std::to_string(pulse.line) +
                             "," + std::to_string(pulse.fiber) + "," +
                             std::to_string(expected[i].r + 1) + "," + fixed_text(pulse.time_s, 9) +
                             "," + fixed_text(ret.range_m, 4) + "," + std::to_string(ret.counter) +
                             "," + fixed_text(enu.x(), 4) + "," + fixed_text(enu.y(), 4) + "," +
                             fixed_text(enu.z(), 4);
    const std::string& row = lines[4 + i];
    ASSERT_TRUE(row.starts_with(head + ",")) << row << "\n" << head;
    EXPECT_TRUE(row.ends_with("," + expected[i].tail)) << row;
    const std::vector<std::string> cells = cells_of(row);
    ASSERT_EQ(cells.size(), 18u) << row;
    // lat, lon, h: the geodetic position of the point, to the 9 and 4 decimals printed.
    const Geodetic g = local_frame_.geodetic_from_enu(enu);
    EXPECT_NEAR(std::stod(cells[11]), g.lat_deg, 0.6e-9);
    EXPECT_NEAR(std::stod(cells[12]), g.lon_deg, 0.6e-9);
    EXPECT_NEAR(std::stod(cells[13]), g.h_m, 0.6e-4);
  }
}

TEST_F(FalseReturnOutputs, LasClassifiesThemLowNoiseAndPlyClassSeven) {
  // LAS 1.4 format 6: 30-byte records from the header's offset; classification at byte 16,
  // intensity at 12, return number in the low nibble of byte 14.
  const std::string& las = files_.at("points.las");
  const auto offset = field<std::uint32_t>(las, 96);
  ASSERT_EQ(field<std::uint64_t>(las, 247), 3u * kFrames);
  const std::uint8_t want_class[] = {7, 7, 14};
  const std::uint16_t want_intensity[] = {190, 190, 819};  // round(e · 65535): T = 0.0029, 0.0125
  for (std::size_t i = 0; i < 3 * kFrames; ++i) {
    const std::size_t record = offset + 30 * i;
    EXPECT_EQ(static_cast<std::uint8_t>(las[record + 16]), want_class[i % 3]) << i;
    EXPECT_EQ(field<std::uint16_t>(las, record + 12), want_intensity[i % 3]) << i;
  }
  // PLY: the 29-byte vertices after the header; the class byte last.
  const std::string& ply = files_.at("points.ply");
  const std::size_t body = ply.find("end_header\n") + 11;
  ASSERT_EQ(ply.size(), body + 29 * 3 * kFrames);
  const std::uint8_t want_ply[] = {7, 7, 0};
  for (std::size_t i = 0; i < 3 * kFrames; ++i) {
    EXPECT_EQ(static_cast<std::uint8_t>(ply[body + 29 * i + 28]), want_ply[i % 3]) << i;
    EXPECT_FLOAT_EQ(field<float>(ply, body + 29 * i + 24), i % 3 < 2 ? 0.0029f : 0.0125f) << i;
  }
  // owsim view reads both back as noise.
  const auto noise = static_cast<std::uint8_t>(SurfaceClass::noise);
  const auto wire = static_cast<std::uint8_t>(SurfaceClass::wire);
  const ReportPoints from_las =
      read_report_points_las(dir_.path() / "run/points.las", local_frame_.origin());
  const ReportPoints from_ply = read_report_points_ply(dir_.path() / "run/points.ply");
  const ReportPoints from_csv = read_report_points_csv(dir_.path() / "run/points.csv");
  for (const ReportPoints* points : {&from_las, &from_ply, &from_csv}) {
    ASSERT_EQ(points->surface.size(), 3u * kFrames) << points->source;
    for (std::size_t i = 0; i < 3 * kFrames; ++i) {
      EXPECT_EQ(points->surface[i], i % 3 < 2 ? noise : wire) << points->source << " " << i;
    }
  }
}

TEST_F(FalseReturnOutputs, WordsHoldTheFalseReturnsCounters) {
  const std::string& words = files_.at("flight.d64");
  ASSERT_EQ(words.size(), 8u * kFrames * scan_.pulses_per_frame());
  const KnownReturns at;
  for (std::int64_t k = 0; k < kFrames; ++k) {
    const auto word_at = [&](std::size_t pulse) {
      return unpack_milows(field<std::uint64_t>(
          words, 8 * (static_cast<std::size_t>(k * scan_.pulses_per_frame()) + pulse)));
    };
    EXPECT_EQ(word_at(at.alone).counter1, counter_from_range(412.5, scan_.counter));
    EXPECT_EQ(word_at(at.alone).counter2, scan_.counter.timeout_counts);
    EXPECT_EQ(word_at(at.before_wire).counter1, counter_from_range(97.25, scan_.counter));
    EXPECT_EQ(word_at(at.before_wire).counter2, counter_from_range(240.0, scan_.counter));
  }
}

TEST_F(FalseReturnOutputs, SummaryCountsThemAndNoObjectGetsThem) {
  const nlohmann::json summary = nlohmann::json::parse(files_.at("summary.json"));
  const auto pulses = static_cast<std::uint64_t>(kFrames * scan_.pulses_per_frame());
  EXPECT_EQ(summary["pulses"], pulses);
  EXPECT_EQ(summary["returns"]["noise"], 2 * kFrames);
  EXPECT_EQ(summary["returns"]["wire"], kFrames);
  EXPECT_EQ(summary["returns"]["ground"], 0);
  EXPECT_EQ(summary["second_returns"], kFrames);
  EXPECT_DOUBLE_EQ(summary["false_returns_per_pulse"].get<double>(),
                   2.0 * kFrames / static_cast<double>(pulses));
  // The wire alone has returns; the false returns are no object's.
  std::uint64_t object_returns = 0;
  for (const nlohmann::json& object : summary["objects"]) {
    object_returns += object["returns"].get<std::uint64_t>();
    if (object["id"] == "span/2") EXPECT_EQ(object["returns"], kFrames);
  }
  EXPECT_EQ(object_returns, static_cast<std::uint64_t>(kFrames));
}

}  // namespace
}  // namespace owsim
