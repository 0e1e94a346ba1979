// Protects the physical ranges of scenario numbers (io/scenario/value_ranges.hpp, issue 17): the
// table equals docs/scenario.md "Allowed ranges" row for row; the hostile values that once
// crashed Embree, hung or ran away in memory (a lever arm of 1e19 m, a pulse rate of 1e12 Hz, a
// 1e308 wire, …) are refused at their line and key with the allowed range, by the loader and by
// validate_scenario for a scenario built in code; a value at either end of its range passes.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/scenario/scenario_check.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/value_ranges.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "minimal_scenario.hpp"
#include "sensor/receiver.hpp"

namespace owsim {
namespace {

constexpr const char* kMinimalScenario = test::kMinimalScenario;

std::string range_error_of(const std::string& yaml) {
  try {
    (void)load_scenario_text(yaml, "s.yaml");
  } catch (const Error& error) {
    return error.what();
  }
  return "accepted";
}

std::string number_text(double value) {
  std::ostringstream text;
  text.precision(9);
  text << value;
  return text.str();
}

TEST(ValueRanges, TheDocumentedTableIsTheCodesTable) {
  std::ifstream doc(OWSIM_SOURCE_DIR "/docs/scenario.md");
  ASSERT_TRUE(doc) << "docs/scenario.md";
  std::string line;
  bool in_section = false;
  std::vector<std::string> documented;
  while (std::getline(doc, line)) {
    if (line.starts_with("## ")) in_section = line == "## Allowed ranges";
    if (in_section && line.starts_with("| `")) documented.push_back(line);
  }
  std::vector<std::string> expected;
  for (const ValueRange& range : value_ranges()) {
    expected.push_back("| `" + std::string(range.key) + "` | " + number_text(range.min) + " | " +
                       number_text(range.max) + " | " + std::string(range.unit) + " |");
  }
  EXPECT_EQ(documented, expected);
}

TEST(ValueRanges, EveryRowIsARangeAndItsEndsPass) {
  for (const ValueRange& range : value_ranges()) {
    SCOPED_TRACE(std::string(range.key));
    EXPECT_LT(range.min, range.max);
    const std::string key = std::string(range.key);
    EXPECT_EQ(out_of_range_problem(key, range.min), "");
    EXPECT_EQ(out_of_range_problem(key, range.max), "");
    EXPECT_NE(out_of_range_problem(key, range.max * 1.5 + 1.0), "");
  }
  EXPECT_EQ(key_pattern("scene.spans[12].layout[3][1]"), "scene.spans[].layout[][]");
  EXPECT_EQ(value_range_of("scene.poles[7].at.e")->key, "<position>.e");
  EXPECT_EQ(value_range_of("origin.e"), nullptr);
  EXPECT_EQ(value_range_of("sensor.model"), nullptr);
}

TEST(ValueRanges, HostileNumbersAreRefusedAtTheirLineAndKey) {
  const std::string m = kMinimalScenario;
  struct Case {
    std::string yaml;
    std::string want;  // the whole message
  };
  const std::vector<Case> cases = {
      {m + "sensor:\n  mount: {lever_arm_m: [0, 0, 1e19]}\n",
       "s.yaml:8: sensor.mount.lever_arm_m[2]: must be in [-50, 50] m, got 1e+19"},
      {"name: m\norigin: {lat: 48, lon: 10, h: 1e308}\n" + m.substr(m.find("trajectory")),
       "s.yaml:2: origin.h: must be in [-1000, 10000] m, got 1e+308"},
      {"name: m\norigin: {lat: 48, lon: 10, h: 0}\ntrajectory:\n  waypoints:\n    speed_mps: 40\n"
       "    points: [{e: 0, n: 0, u: 1e19}, {e: 100, n: 0, u: 100}]\n",
       "s.yaml:6: trajectory.waypoints.points[0].u: must be in [-1000, 10000] m, got 1e+19"},
      {m + "sensor:\n  prf_hz: 1e12\n",
       "s.yaml:8: sensor.prf_hz: must be in [1, 1000000] Hz, got 1e+12"},
      {m + "sensor:\n  sawtooth_deg: 1e308\n",
       "s.yaml:8: sensor.sawtooth_deg: must be in [0, 10] deg, got 1e+308"},
      {m + "sensor:\n  lines_per_frame: 1000000000\n",
       "s.yaml:8: sensor.lines_per_frame: must be in [1, 10000], got 1000000000"},
      {m + "scene:\n  spans:\n    - {id: s, from: {e: 0, n: 0}, to: {e: 90, n: 0}, "
           "conductor: {diameter_mm: 1e308}}\n",
       "s.yaml:9: scene.spans[0].conductor.diameter_mm: must be in [1, 200] mm, got 1e+308"},
      {m.substr(0, m.find("speed_mps")) + "speed_mps: 0.001\n    points: [{e: 0, n: 0, u: 100}, "
                                          "{e: 100, n: 0, u: 100}]\n",
       "s.yaml:5: trajectory.waypoints.speed_mps: must be in [1, 150] m/s, got 0.001"},
      {m + "scene:\n  forest: {count: 10000000}\n",
       "s.yaml:8: scene.forest.count: must be in [0, 1000000], got 10000000"},
      {m + "scene:\n  poles:\n    - {id: p, at: {e: 1e7, n: 0}, height_m: 5, diameter_m: 1}\n",
       "s.yaml:9: scene.poles[0].at.e: must be in [-200000, 200000] m, got 10000000"},
      // Issue 33: weather's numbers gave energies of 1e299 or NaN.
      {m + "weather:\n  fog: [{id: f, visibility_m: 1e-300}]\n",
       "s.yaml:8: weather.fog[0].visibility_m: must be in [1, 100000] m, got 1e-300"},
      {m + "weather:\n  fog: [{id: f, visibility_m: 4.9e-324}]\n",
       "s.yaml:8: weather.fog[0].visibility_m: must be in [1, 100000] m, got 4.94065646e-324"},
      {m + "weather:\n  backscatter_ratio_sr: 1e308\n",
       "s.yaml:8: weather.backscatter_ratio_sr: must be in [0, 1] sr^-1, got 1e+308"},
      {m + "weather:\n  fog: [{id: f, visibility_m: 20, layer: {base_m: 0, top_m: 1e9}}]\n",
       "s.yaml:8: weather.fog[0].layer.top_m: must be in [-1000, 10000] m, got 1000000000"},
      {m + "weather:\n  fog: [{id: terrain, visibility_m: 20}]\n",
       "s.yaml:8: weather.fog[0].id: 'terrain' is the ground's id (points.csv's object column)"},
  };
  for (const Case& c : cases) EXPECT_EQ(range_error_of(c.yaml), c.want) << c.yaml;
}

TEST(ValueRanges, SizesThatOnlyTogetherRunAwayAreRefused) {
  // Each within its range, together a frame of 10 M pulses or a route of 4.6 days whose samples
  // are all held in memory.
  const std::string frame = range_error_of(
      std::string(kMinimalScenario) + "sensor: {fibers_per_line: 1024, lines_per_frame: 10000}\n");
  EXPECT_NE(frame.find("sensor.lines_per_frame: fibers_per_line × lines_per_frame = 10240000 "
                       "pulses per frame, more than 1048576"),
            std::string::npos)
      << frame;
  Scenario crawl = load_scenario_text(kMinimalScenario, "s.yaml");
  crawl.trajectory.speed_mps = 1.0;
  crawl.trajectory.waypoints_enu_m = {{-199'000.0, 0.0, 100.0}, {199'000.0, 0.0, 100.0}};
  try {
    (void)load_trajectory(crawl, LocalFrame(crawl.origin));
    FAIL() << "planned a route of 398 km at 1 m/s";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "s.yaml: trajectory.waypoints: the route takes 398000 s at 1 m/s; owsim flies "
              "routes of up to 86400 s");
  }
}

TEST(ValueRanges, AScenarioBuiltInCodeIsHeldToTheSameTable) {
  const Scenario base = load_scenario_text(kMinimalScenario, "s.yaml");
  const auto error_of_built = [&](auto change) -> std::string {
    Scenario scenario = base;
    change(scenario);
    try {
      validate_scenario(scenario);
    } catch (const Error& error) {
      return error.what();
    }
    return "accepted";
  };
  EXPECT_EQ(error_of_built([](Scenario&) {}), "accepted");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.mount.lever_arm_m.z() = 1e19; }),
            "sensor.mount.lever_arm_m[2]: must be in [-50, 50] m, got 1e+19");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.trajectory.waypoints_enu_m[1].x() = 3e5; }),
            "trajectory.waypoints.points[1].e: must be in [-200000, 200000] m, got 300000");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.scan.prf_hz = 1e12; }),
            "sensor.prf_hz: must be in [1, 1000000] Hz, got 1e+12");
  FogVolume fog;
  fog.id = "f";
  fog.visibility_m = 1e-300;
  EXPECT_EQ(error_of_built([&](Scenario& s) { s.scene.fog = {fog}; }),
            "weather.fog[0].visibility_m: must be in [1, 100000] m, got 1e-300");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.scene.fog_backscatter_ratio_sr = 1e308; }),
            "weather.backscatter_ratio_sr: must be in [0, 1] sr^-1, got 1e+308");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.receiver.noise.noise_at_1km = -1.0; }),
            "sensor.receiver.noise_at_1km: must be in [0, 1], got -1");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.receiver.noise.pulse_width_ns = 0.0; }),
            "sensor.receiver.pulse_width_ns: must be in [0.1, 1000] ns, got 0");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.receiver.noise.sun_noise = -2.0; }),
            "sensor.receiver.sun_noise: must be in [0, 1000], got -2");
  EXPECT_EQ(error_of_built([](Scenario& s) { s.receiver.noise.sky_noise = -0.5; }),
            "sensor.receiver.sky_noise: must be in [0, 1000], got -0.5");
  EXPECT_EQ(error_of_built([](Scenario& s) {
              s.receiver.sun = {.given = true, .elevation_deg = 200.0, .azimuth_deg = 0.0};
            }),
            "sun.elevation_deg: must be in [-90, 90] deg, got 200");
  // Night: the angles of a sun not given are not read.
  EXPECT_EQ(error_of_built([](Scenario& s) { s.receiver.sun.elevation_deg = 200.0; }), "accepted");
  fog.visibility_m = 20.0;
  fog.id = "terrain";
  EXPECT_EQ(error_of_built([&](Scenario& s) { s.scene.fog = {fog}; }),
            "weather.fog[0].id: 'terrain' is the ground's id (points.csv's object column)");
}

// validate(ReceiverParams) (sensor/receiver.hpp), what the receiver itself relies on, refuses
// what the table cannot say: a NaN anywhere, an infinite azimuth.
TEST(ValueRanges, TheReceiverRefusesNonFiniteStatisticsAndSun) {
  const auto error_of_receiver = [](auto change) -> std::string {
    ReceiverParams receiver;
    change(receiver);
    try {
      validate(receiver);
    } catch (const Error& error) {
      return error.what();
    }
    return "accepted";
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of_receiver([](ReceiverParams&) {}), "accepted");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) { p.noise.noise_at_1km = nan; }),
            "sensor.receiver.noise_at_1km: must be a finite number ≥ 0, got nan");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) { p.noise.pulse_width_ns = -1.0; }),
            "sensor.receiver.pulse_width_ns: must be a finite number > 0, got -1");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) { p.noise.sun_noise = inf; }),
            "sensor.receiver.sun_noise: must be a finite number ≥ 0, got inf");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) { p.noise.sky_noise = -1e-9; }),
            "sensor.receiver.sky_noise: must be a finite number ≥ 0, got -1e-09");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) {
              p.sun = {true, nan, 0.0};
            }),
            "sun.elevation_deg: must be in [-90, 90] deg, got nan");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) {
              p.sun = {true, 45.0, inf};
            }),
            "sun.azimuth_deg: must be a finite angle clockwise from north, got inf");
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) {
              p.sun = {true, 45.0, -400.0};
            }),
            "accepted");  // any finite azimuth: the direction is its sine and cosine
  EXPECT_EQ(error_of_receiver([&](ReceiverParams& p) { p.sun = {false, nan, inf}; }), "accepted");
}

TEST(ValueRanges, TooManyFogVolumesAreRefusedAtTheirLine) {
  std::string yaml = std::string(kMinimalScenario) + "weather:\n  fog:\n";
  for (int i = 0; i < 33; ++i) yaml += "    - {id: f" + std::to_string(i) + ", visibility_m: 20}\n";
  EXPECT_EQ(range_error_of(yaml), "s.yaml:8: weather.fog: at most 32 volumes, got 33");
}

}  // namespace
}  // namespace owsim
