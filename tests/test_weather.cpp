// Protects fog and cloud (SENSOR-SPEC §10; geometry/fog_volume.hpp, sensor/weather.hpp): the
// spec's numbers (α from visibility, the smallest α that registers, the busy length), the exact
// path of a ray through layers and boxes against sampling, the optical depth against numerical
// integration over overlapping volumes, the busy interval hiding what lies inside it, a run
// through a fog layer against a closed-form oracle (tests/oracles/weather_oracle.py: entry range,
// volume energy, busy end, the attenuated echo behind, which return each lands in, the words),
// the fog_bank example (MilOWS sees the wire as return 2, HELLAS's words never), and bad weather
// keys giving one line and no output.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <string>

#include "cli_runner.hpp"
#include "geometry/fog_volume.hpp"
#include "python_oracle.hpp"
#include "sensor/weather.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

TEST(Weather, SpecNumbers) {
  EXPECT_DOUBLE_EQ(fog_extinction_per_m(20.0), 3.912 / 20.0);
  EXPECT_NEAR(fog_extinction_per_m(1000.0), 0.003912, 1e-15);
  // §10 sanity: a medium registers at all only when π·κ·α·L ≥ 0.005, i.e. α ≥ 0.138 /m.
  const double smallest = 0.005 / (std::numbers::pi * 0.0154 * 0.75);
  EXPECT_NEAR(smallest, 0.1378, 5e-5);
  EXPECT_NEAR(volume_echo_energy(smallest, 0.0154, 0.75, 0.0, 1.0), 0.005, 1e-15);
  EXPECT_NEAR(volume_echo_energy(0.2, 0.0154, 0.75, 0.0, 1.0),
              std::numbers::pi * 0.0154 * 0.2 * 0.75, 1e-15);
  // Behind D metres of medium a wire keeps exp(−2αD) of its energy.
  EXPECT_NEAR(fog_transmission(0.2 * 3.0), std::exp(-1.2), 1e-15);
  // Inside a volume the echo stays above the threshold for ln(e/thr) / (2α) past its entry.
  const double e0 = volume_echo_energy(0.25, 0.0154, 0.75, 0.0, 1.0);
  const double busy = volume_busy_length_m(e0, 0.005, 0.25, 0.0);
  EXPECT_NEAR(busy, std::log(e0 / 0.005) / 0.5, 1e-15);
  EXPECT_NEAR(volume_echo_energy(0.25, 0.0154, 0.75, 0.25 * busy, 1.0), 0.005, 1e-15);
}

TEST(FogVolume, PathsThroughLayersAndBoxes) {
  FogVolume layer;
  layer.shape = FogShape::layer;
  layer.base_m = 10.0;
  layer.top_m = 12.0;
  const Eigen::Vector3d down = Eigen::Vector3d(0.0, 0.6, -0.8);
  const auto through = path_interval(layer, {0.0, 0.0, 20.0}, down, 1000.0);
  ASSERT_TRUE(through);
  EXPECT_NEAR(through->enter_m, 8.0 / 0.8, 1e-12);
  EXPECT_NEAR(through->exit_m, 10.0 / 0.8, 1e-12);
  EXPECT_FALSE(path_interval(layer, {0.0, 0.0, 20.0}, Eigen::Vector3d::UnitY(), 1000.0));
  const auto inside = path_interval(layer, {0.0, 0.0, 11.0}, Eigen::Vector3d::UnitY(), 50.0);
  ASSERT_TRUE(inside);
  EXPECT_EQ(inside->enter_m, 0.0);
  EXPECT_EQ(inside->exit_m, 50.0);
  const auto short_ray = path_interval(layer, {0.0, 0.0, 20.0}, down, 11.0);  // ends inside
  ASSERT_TRUE(short_ray);
  EXPECT_EQ(short_ray->exit_m, 11.0);

  // Random rays against random boxes and layers: the interval holds exactly the sampled points
  // inside the volume.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  int crossed = 0;
  for (int i = 0; i < 2000; ++i) {
    FogVolume volume;
    volume.shape = i % 3 == 0 ? FogShape::layer : FogShape::box;
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    volume.box = Eigen::AlignedBox3d(a.cwiseMin(b), a.cwiseMax(b));
    volume.base_m = volume.box.min().z();
    volume.top_m = volume.box.max().z();
    const Eigen::Vector3d origin(u(rng), u(rng), u(rng));
    const Eigen::Vector3d dir = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const auto interval = path_interval(volume, origin, dir, 120.0);
    crossed += interval ? 1 : 0;
    for (int k = 0; k <= 600; ++k) {
      const double t = 0.2 * k;
      const Eigen::Vector3d p = origin + t * dir;
      const bool in = volume.shape == FogShape::layer
                          ? p.z() >= volume.base_m && p.z() <= volume.top_m
                          : volume.box.contains(p);
      const bool claimed = interval && t >= interval->enter_m && t <= interval->exit_m;
      // Points within a micrometre of a face may fall either way.
      const double margin =
          volume.shape == FogShape::layer
              ? std::min(std::abs(p.z() - volume.base_m), std::abs(p.z() - volume.top_m))
              : volume.box.exteriorDistance(p) +
                    (in ? (volume.box.max() - p).cwiseMin(p - volume.box.min()).minCoeff() : 0.0);
      if (margin < 1e-6) continue;
      ASSERT_EQ(in, claimed) << "ray " << i << " t " << t;
    }
  }
  EXPECT_GT(crossed, 300);
}

TEST(MediumPath, OpticalDepthIsTheIntegralOverOverlappingVolumes) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  for (int i = 0; i < 200; ++i) {
    std::vector<FogVolume> fog;
    for (int v = 0; v < 4; ++v) {
      FogVolume volume;
      volume.id = "v" + std::to_string(v);
      volume.visibility_m = 20.0 + 200.0 * std::abs(u(rng)) / 100.0;
      volume.shape = v == 3 ? FogShape::layer : FogShape::box;
      const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
      volume.box = Eigen::AlignedBox3d(a.cwiseMin(b), a.cwiseMax(b));
      volume.base_m = volume.box.min().z();
      volume.top_m = volume.box.max().z();
      fog.push_back(volume);
    }
    const WeatherMedia media(fog, 0.0154, 10, ReceiverParams{});
    const PulseRay ray{{u(rng), u(rng), u(rng)},
                       Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()};
    const MediumPath path(media, ray, 300.0, ReceiverParams{});
    // Midpoint rule over 1 cm steps.
    double depth = 0.0;
    for (int k = 0; k < 25'000; ++k) {
      const Eigen::Vector3d p = ray.origin_enu_m + (0.01 * k + 0.005) * ray.dir_enu;
      for (std::size_t v = 0; v < fog.size(); ++v) {
        const bool in = fog[v].shape == FogShape::layer
                            ? p.z() >= fog[v].base_m && p.z() <= fog[v].top_m
                            : fog[v].box.contains(p);
        if (in) depth += 0.01 * media.extinction_per_m[v];
      }
    }
    ASSERT_NEAR(path.optical_depth(250.0), depth, 0.01 * 0.2 * 8) << "ray " << i;
  }
}

// A 4 m fog bank (visibility 15 m, α = 0.2608) 100 m ahead along +n: its echo holds the receiver
// for ln(e/0.005)/(2α) ≈ 0.97 m past the entry.
struct BankAhead {
  BankAhead() : media({volume()}, 0.0154, 7, receiver) {}
  static ReceiverParams threshold_0_005() {
    ReceiverParams r;
    r.threshold = 0.005;
    return r;
  }
  static FogVolume volume() {
    FogVolume bank;
    bank.id = "bank";
    bank.visibility_m = 15.0;
    bank.shape = FogShape::box;
    bank.box = Eigen::AlignedBox3d(Eigen::Vector3d(-10, 100, -10), Eigen::Vector3d(10, 104, 10));
    return bank;
  }
  ReceiverParams receiver = threshold_0_005();
  WeatherMedia media;
  PulseRay ray{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()};
  double alpha = fog_extinction_per_m(15.0);
  double echo = volume_echo_energy(alpha, 0.0154, 0.75, 0.0, 0.95);
  double busy_end = 100.0 + std::log(echo / 0.005) / (2.0 * alpha);
};

// A wire inside the interval a fog echo holds the receiver is not seen; one behind is, attenuated;
// one in front is untouched.
TEST(MediumPath, TheBusyIntervalHidesWhatLiesInsideIt) {
  const BankAhead bank;
  std::array<Candidate, 8> buffer{};
  buffer[0] = Candidate{50.0, 0.2, 0.0, 0, 0};                  // in front of the bank
  buffer[1] = Candidate{100.5, 0.2, 0.0, 1, 0};                 // inside the busy interval
  buffer[2] = Candidate{bank.busy_end + 0.01, 0.2, 0.0, 2, 0};  // inside the bank, past it
  buffer[3] = Candidate{110.0, 0.2, 0.0, 3, 0};                 // behind the bank
  const std::size_t n = apply_weather(bank.media, bank.ray, 200.0, bank.receiver, buffer, 4);
  ASSERT_EQ(n, 4u);
  EXPECT_EQ(buffer[0].object_index, 0u);
  EXPECT_EQ(buffer[0].energy_rel, 0.2);
  EXPECT_EQ(buffer[1].object_index, 2u);
  EXPECT_NEAR(buffer[1].energy_rel,
              0.2 * std::exp(-2.0 * bank.alpha * (bank.busy_end + 0.01 - 100.0)), 1e-15);
  EXPECT_EQ(buffer[2].object_index, 3u);
  EXPECT_NEAR(buffer[2].energy_rel, 0.2 * std::exp(-2.0 * bank.alpha * 4.0), 1e-15);
  EXPECT_EQ(buffer[3].object_index, 7u);  // the bank, the media's first object
  EXPECT_EQ(buffer[3].surface, static_cast<std::uint8_t>(SurfaceClass::fog));
  EXPECT_DOUBLE_EQ(buffer[3].range_m, 100.0);
  EXPECT_NEAR(buffer[3].energy_rel, bank.echo, 1e-15);
  // The solid ends the path: a bank behind it adds nothing.
  EXPECT_EQ(apply_weather(bank.media, bank.ray, 80.0, bank.receiver, buffer, 0), 0u);
}

// Issue 33: a solid met inside the busy interval (the ground 0.5 m into the bank) merges into the
// volume's return — the echo never falls below the threshold — and is not a second return; one
// met after the interval is.
TEST(MediumPath, ASolidInsideTheBusyIntervalIsNotANewReturn) {
  const BankAhead bank;
  ASSERT_GT(bank.busy_end, 100.8);
  for (const double solid_m : {100.5, 100.8, bank.busy_end - 1e-6}) {
    SCOPED_TRACE(solid_m);
    std::array<Candidate, 8> buffer{};
    buffer[0] = Candidate{solid_m, 0.3, 0.0, 1, 0};
    ASSERT_EQ(apply_weather(bank.media, bank.ray, solid_m, bank.receiver, buffer, 1), 1u);
    EXPECT_EQ(buffer[0].object_index, 7u);  // the bank alone
    EXPECT_DOUBLE_EQ(buffer[0].range_m, 100.0);
  }
  std::array<Candidate, 8> buffer{};
  buffer[0] = Candidate{bank.busy_end + 0.01, 0.3, 0.0, 1, 0};
  ASSERT_EQ(apply_weather(bank.media, bank.ray, bank.busy_end + 0.01, bank.receiver, buffer, 1),
            2u);
  EXPECT_EQ(buffer[0].object_index, 1u);  // the solid, behind the interval
  EXPECT_EQ(buffer[1].object_index, 7u);
}

// Issue 44 item 6, fog standing on flat ground: the ground and the fog's floor are one plane, but
// the ground's range (its triangle, in double) lies 1.1e-13 m past the floor's slab exit. The
// ground was then taken as behind the medium, the busy interval (0.7643 m with T_atm 0.95) cut at
// the floor, and the ground 0.756 m behind the fog's entry became a second return. The ray and the
// ground's range are those of fog_bank's frame 1, pulse 11187 (owsim 0.1.0, `owsim run
// examples/fog_bank.yaml --no-noise`); the same ray ends in a 0.105 m layer of the same fog.
TEST(MediumPath, TheGroundUnderAFogIsInsideIt) {
  const PulseRay ray{{-579.3562533750062, 1.2640649113353857e-15, 60.0},
                     {0.9898247165000341, 0.03019562903523729, -0.13905126605965723}};
  const double ground_m = 431.4955318296648;
  ASSERT_NEAR(ray.origin_enu_m.z() + ground_m * ray.dir_enu.z(), 0.0, 1e-12);
  FogVolume bank;
  bank.id = "bank";
  bank.visibility_m = 20.0;
  bank.shape = FogShape::box;
  bank.box = Eigen::AlignedBox3d(Eigen::Vector3d(-153, -400, 0), Eigen::Vector3d(-150, 400, 150));
  FogVolume layer = bank;
  layer.shape = FogShape::layer;
  layer.base_m = 0.0;
  layer.top_m = 0.105;
  ReceiverParams receiver;
  receiver.threshold = 0.005;
  receiver.atmosphere.transmission = 0.95;
  for (const FogVolume& fog : {bank, layer}) {
    SCOPED_TRACE(fog.shape == FogShape::box ? "box" : "layer");
    const auto through = path_interval(fog, ray.origin_enu_m, ray.dir_enu, ground_m);
    ASSERT_TRUE(through.has_value());
    EXPECT_LT(through->exit_m, ground_m);  // the rounding: the floor a hair before the ground
    EXPECT_GT(through->exit_m, ground_m - 1e-12);
    const WeatherMedia media({fog}, 0.0154, 7, receiver);
    EXPECT_NEAR(media.entry_busy_m[0], 0.76432, 1e-5);
    // Behind the fog's return by more than the return separation, inside the busy interval.
    ASSERT_GT(ground_m - through->enter_m, receiver.min_return_separation_m);
    ASSERT_LT(ground_m - through->enter_m, media.entry_busy_m[0]);
    std::array<Candidate, 8> buffer{};
    buffer[0] =
        Candidate{ground_m, 0.00507, 82.0, 0, static_cast<std::uint8_t>(SurfaceClass::ground)};
    ASSERT_EQ(apply_weather(media, ray, ground_m, receiver, buffer, 1), 1u);
    EXPECT_EQ(buffer[0].object_index, 7u);  // the fog alone: the ground merged into its return
    EXPECT_EQ(buffer[0].range_m, through->enter_m);
  }
}

const char* kLayerScenario = R"(name: layer
seed: 9
origin: {lat: 48.6881, lon: 10.8447, h: 450.0}
sensor: {model: milows, threshold: 0.005,
         mount: {roll_deg: 0, pitch_deg: -25, yaw_deg: 0, lever_arm_m: [0, 0, 0]}}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: -300, n: 0, u: 60}, {e: 200, n: 0, u: 60}]
scene:
  terrain: {flat_u: 0}
  spans:
    - {id: s, from: {e: 0, n: -200}, to: {e: 0, n: 200}, support_heights_m: [30, 30],
       lowest_point_m: 22, layout: tri, conductor: {diameter_mm: 30}}
)";

class WeatherRuns : public ::testing::Test {
 protected:
  CliResult run(const std::string& name, const std::string& yaml, const std::string& frames) {
    std::ofstream(dir_ / (name + ".yaml")) << yaml;
    return run_cli({"run", (dir_ / (name + ".yaml")).string(), "--no-noise", "--frames", frames,
                    "--outputs", "points,d64,summary", "--out", (dir_ / name).string()},
                   dir_.path());
  }
  TempDir dir_{"owsim_weather"};
};

TEST_F(WeatherRuns, ALayerOfFogMatchesTheClosedForm) {
  const std::string weather =
      "weather:\n  fog:\n    - {id: deck, visibility_m: 20, layer: {base_m: 45, top_m: 46}}\n";
  ASSERT_EQ(run("fog", std::string(kLayerScenario) + weather, "6").exit_status, 0);
  ASSERT_EQ(run("clear", kLayerScenario, "6").exit_status, 0);
  const CliResult decoded =
      run_cli({"decode", (dir_ / "fog/flight.d64").string(), "--scenario",
               (dir_ / "fog.yaml").string(), "--out", (dir_ / "decoded").string(), "--quiet"},
              dir_.path());
  ASSERT_EQ(decoded.exit_status, 0) << decoded.err;
  const std::string verdict = test::run_python_file(
      fs::path(OWSIM_SOURCE_DIR) / "tests/oracles/weather_oracle.py",
      {(dir_ / "fog/points.csv").string() + " " + (dir_ / "clear/points.csv").string() + " " +
           (dir_ / "decoded/points.csv").string() + " 45 46 20 0.0154 0.95 0.005",
       false});
  ASSERT_EQ(verdict.rfind("ok ", 0), 0u) << verdict;
  long fog = 0, behind = 0, hidden = 0;
  ASSERT_EQ(std::sscanf(verdict.c_str(), "ok %ld %ld %ld", &fog, &behind, &hidden), 3);
  EXPECT_GT(fog, 100'000);
  EXPECT_GT(behind, 50'000);  // the ground and the wires behind 1–2 m of fog
  EXPECT_GT(hidden, 10'000);  // those the fog dims below the threshold

  std::ifstream file(dir_ / "fog/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(file);
  EXPECT_EQ(summary["returns"]["fog"], fog);
  // Every wire return came through the deck: seen through fog, never clear.
  long wire_returns = 0;
  for (const auto& object : summary["objects"]) {
    if (object["class"] != "wire" || object["returns"] == 0) continue;
    wire_returns += object["returns"].get<long>();
    EXPECT_EQ(object["seen_through_fog"], object["returns"]) << object.dump();
    EXPECT_TRUE(object["first_seen_clear_range_m"].is_null()) << object.dump();
  }
  EXPECT_GT(wire_returns, 10);  // 6 frames: the wires come into view at the end
  std::ifstream clear_file(dir_ / "clear/summary.json");
  const nlohmann::json clear = nlohmann::json::parse(clear_file);
  EXPECT_FALSE(clear["returns"].contains("fog"));
  EXPECT_FALSE(clear["objects"][0].contains("seen_through_fog"));
}

// The example's first 10 s, the bank between the helicopter and the span: MilOWS records the wire
// behind the bank as return 2; HELLAS, whose word holds the first return only, reports the bank
// where MilOWS saw both.
TEST_F(WeatherRuns, FogBankExampleMilowsSeesTheWireBehindHellasDoesNot) {
  std::ifstream example(fs::path(OWSIM_SOURCE_DIR) / "examples/fog_bank.yaml");
  const std::string yaml((std::istreambuf_iterator<char>(example)),
                         std::istreambuf_iterator<char>());
  std::string hellas = yaml;
  hellas.replace(hellas.find("model: milows"), 13, "model: hellas");
  const auto wires_by_return = [&](const std::string& name, const std::string& text,
                                   const char* words) {
    std::ofstream(dir_ / (name + ".yaml")) << text;
    const CliResult result =
        run_cli({"run", (dir_ / (name + ".yaml")).string(), "--no-noise", "--frames", "30",
                 "--outputs", "d64", "--out", (dir_ / name).string()},
                dir_.path());
    EXPECT_EQ(result.exit_status, 0) << result.err;
    const CliResult decoded = run_cli(
        {"decode", (dir_ / name / words).string(), "--scenario", (dir_ / (name + ".yaml")).string(),
         "--out", (dir_ / (name + "_points")).string(), "--quiet"},
        dir_.path());
    EXPECT_EQ(decoded.exit_status, 0) << decoded.err;
    std::map<std::string, int> counts;
    std::ifstream points(dir_ / (name + "_points") / "points.csv");
    std::string line;
    while (std::getline(points, line)) {
      if (line.find(",wire,") == std::string::npos) continue;
      const std::size_t comma =
          line.find(',', line.find(',', line.find(',', line.find(',') + 1) + 1) + 1);
      counts[line.substr(comma + 1, 1)] += 1;  // the `return` column
    }
    return counts;
  };
  const auto milows = wires_by_return("milows", yaml, "flight.d64");
  EXPECT_GT(milows.count("2") ? milows.at("2") : 0, 100);
  const auto hellas_counts = wires_by_return("hellas", hellas, "flight.hellas");
  EXPECT_TRUE(hellas_counts.empty());
}

// Issue 33 (SENSOR-SPEC §8): a HELLAS run's points are what its words hold — the first return of
// each pulse, as its decode gives them — not the second returns (the wire behind the fog) the
// receiver found but the 32-bit word cannot carry.
TEST_F(WeatherRuns, HellasPointsAreWhatItsWordsHold) {
  std::ifstream example(fs::path(OWSIM_SOURCE_DIR) / "examples/fog_bank.yaml");
  std::string yaml((std::istreambuf_iterator<char>(example)), std::istreambuf_iterator<char>());
  yaml.replace(yaml.find("model: milows"), 13, "model: hellas");
  std::ofstream(dir_ / "hellas.yaml") << yaml;
  const CliResult result =
      run_cli({"run", (dir_ / "hellas.yaml").string(), "--no-noise", "--frames", "12", "--outputs",
               "d64,csv", "--out", (dir_ / "run").string()},
              dir_.path());
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const CliResult decoded =
      run_cli({"decode", (dir_ / "run/flight.hellas").string(), "--scenario",
               (dir_ / "hellas.yaml").string(), "--out", (dir_ / "decoded").string(), "--quiet"},
              dir_.path());
  ASSERT_EQ(decoded.exit_status, 0) << decoded.err;
  // (frame, pulse, return) of every row.
  const auto keys = [](const fs::path& file) {
    std::vector<std::string> out;
    std::ifstream points(file);
    std::string line;
    std::getline(points, line);  // header
    while (std::getline(points, line)) {
      std::size_t at = 0;
      for (int comma = 0; comma < 2; ++comma) at = line.find(',', at) + 1;
      const std::size_t fiber_end = line.find(',', line.find(',', at) + 1);
      out.push_back(line.substr(0, at) + line.substr(fiber_end + 1, 1));
    }
    return out;
  };
  const std::vector<std::string> simulated = keys(dir_ / "run/points.csv");
  EXPECT_GT(simulated.size(), 10'000u);
  EXPECT_EQ(simulated, keys(dir_ / "decoded/points.csv"));
  EXPECT_EQ(std::count_if(simulated.begin(), simulated.end(),
                          [](const std::string& key) { return key.back() != '1'; }),
            0);
}

TEST_F(WeatherRuns, BadWeatherGivesOneLineAndNoOutput) {
  const struct {
    std::string weather;
    std::string says;
  } cases[] = {
      {"{fog: [{id: f, visibility_m: 0}]}", "weather.fog[0].visibility_m"},
      {"{fog: [{id: f, visibility_m: -5, layer: {base_m: 0, top_m: 10}}]}", "visibility_m"},
      {"{fog: [{id: f, visibility_m: 20, layer: {base_m: 50, top_m: 40}}]}", "top"},
      {"{fog: [{id: f, visibility_m: 20, sphere: {radius_m: 10}}]}", "sphere"},
      {"{fog: [{id: f, visibility_m: 20, box: {e: [0, 10], n: [5, 5], u: [0, 9]}}]}", "min < max"},
      {"{backscatter_ratio_sr: -1}", "backscatter_ratio_sr"},
      {"{fog: [{id: s, visibility_m: 20}]}", "duplicate id"},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.weather);
    const CliResult result =
        run("bad", std::string(kLayerScenario) + "weather: " + bad.weather + "\n", "2");
    EXPECT_NE(result.exit_status, 0);
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find(bad.says), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
}

// A fog layer merged into a recording of empty sky writes the words of the fog flown alone.
TEST_F(WeatherRuns, MergingFogIntoAnEmptySkyEqualsFlyingIt) {
  std::string sky = kLayerScenario;
  sky.replace(sky.find("terrain: {flat_u: 0}"), 20, "terrain: none");
  sky.erase(sky.find("  spans:"));
  const std::string fog =
      sky +
      "weather:\n  fog:\n    - {id: deck, visibility_m: 20, layer: {base_m: 45, top_m: 46}}\n";
  ASSERT_EQ(run("sky", sky, "3").exit_status, 0);
  ASSERT_EQ(run("fog", fog, "3").exit_status, 0);
  const CliResult merged = run_cli(
      {"merge", (dir_ / "sky/flight.d64").string(), "--scenario", (dir_ / "fog.yaml").string(),
       "--out", (dir_ / "merged.d64").string(), "--no-noise", "--quiet"},
      dir_.path());
  ASSERT_EQ(merged.exit_status, 0) << merged.err;
  const std::string words = test::read_whole_file(dir_ / "fog/flight.d64");
  EXPECT_GT(words.size(), 100'000u);
  EXPECT_TRUE(test::read_whole_file(dir_ / "merged.d64") == words);
}

// A weather key without volumes changes nothing: every output byte for byte the clear run's.
TEST_F(WeatherRuns, WeatherWithoutVolumesChangesNoByte) {
  ASSERT_EQ(run("plain", kLayerScenario, "3").exit_status, 0);
  ASSERT_EQ(
      run("empty", std::string(kLayerScenario) + "weather: {backscatter_ratio_sr: 0.03}\n", "3")
          .exit_status,
      0);
  for (const char* file : {"flight.d64", "points.csv", "points.ply"}) {
    EXPECT_EQ(test::read_whole_file(dir_ / "plain" / file),
              test::read_whole_file(dir_ / "empty" / file))
        << file;
  }
}

}  // namespace
}  // namespace owsim
