// Protects the scenario loader (io/scenario/scenario_loader.hpp, INTERFACE.md "Scenario file"):
// every key lands in its field, the spec's defaults hold, the three position forms agree (pyproj
// oracle), and every bad input is one error line naming the file, the line and the dotted key path.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "geometry/error.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"
#include "io/scenario/solar_position.hpp"
#include "minimal_scenario.hpp"
#include "python_oracle.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

using test::run_python;

// INTERFACE.md's example scenario, as printed there.
constexpr const char* kInterfaceExample =
    R"(name: single_span                # used for the default output folder
seed: 42                         # all randomness derives from it
origin: {lat: 48.6881, lon: 10.8447, h: 450.0}   # local ENU origin, WGS-84

sensor:
  model: milows                  # milows | hellas
  mount: {roll_deg: 0, pitch_deg: -4, yaw_deg: 0, lever_arm_m: [0, 0, 0]}
  divergence_mrad: 1.0           # full angle
  threshold: 0.005               # minimum received/transmitted energy ratio
  range_noise_sigma_m: 0.4241    # 0 disables
  returns: first_second          # first_second | strongest
  # any SENSOR-SPEC constant may be overridden here under its documented name

atmosphere: {transmission: 0.95} # two-way; or {visibility_km: 5}

trajectory:                      # exactly one source
  waypoints:
    speed_mps: 40
    points:                      # positions as {e,n,u}, {lat,lon,h} or {utm: "32U 634000 5394000", h: 560}
      - {e: -1200, n: 0, u: 100}
      - {e: 400, n: 0, u: 100}
  # file: flight.txt             # or a recorded trajectory
  # format: hellsim              # hellsim | csv | sbet
  #   csv: columns read by header name — time_s, lat_deg, lon_deg, h_m, roll_deg,
  #   pitch_deg, heading_deg (others ignored), so a trajectory.csv written by owsim reads back
  # tick_s: 0.0005               # HellSim time-tag weight
  # heading: true                # true | magnetic (then magnetic_variation_deg)
  # smoothing: {window: 9, degree: 3}
  # irs_noise: true              # add the IRS error model of SENSOR-SPEC §5
  start_s: 0
  duration_s: 30

scene:
  terrain: {flat_u: 0}           # or {grid: dem.asc} (ESRI ASCII grid in the local frame), or none
  spans:
    - id: line-a
      from: {e: 0, n: -200}
      to:   {e: 0, n: 200}
      support_heights_m: [30, 30] # H1, H2 above terrain
      lowest_point_m: 20          # S: height of the sag's lowest point above terrain
      layout: single              # single | tri | sept | [[dy, dz], ...] conductor offsets in metres
      conductor: {diameter_mm: 20, reflectivity: 0.4}
      supports: {kind: pole, diameter_m: 0.5, reflectivity: 0.3}   # or kind: none
  poles:
    - {id: p1, at: {e: 50, n: 50}, height_m: 25, diameter_m: 0.4, reflectivity: 0.3}
  trees:
    - {id: t1, at: {lat: 48.689, lon: 10.846}, height_m: 15, diameter_m: 4, reflectivity: 0.2}
  forest: {count: 0, area: {e: [-500, 500], n: [-500, 500]}, height_m: [8, 25], diameter_m: [2, 8]}
)";

// Six lines: name, origin, and the shortest trajectory. Cases append from line 7 on.
constexpr const char* kMinimal = test::kMinimalScenario;

const std::filesystem::path kPath = "/scenarios/s.yaml";  // never read: text is loaded in memory

std::string error_of(const std::string& yaml, const std::filesystem::path& path = kPath) {
  try {
    (void)load_scenario_text(yaml, path);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "accepted:\n" << yaml;
  return {};
}

// The error starts with "<file>:<line>: <key>: " and contains `problem`.
void expect_error(const std::string& yaml, int line, const std::string& key,
                  const std::string& problem) {
  const std::string message = error_of(yaml);
  const std::string where = kPath.string() + ":" + std::to_string(line) + ": " + key + ": ";
  EXPECT_EQ(message.rfind(where, 0), 0u) << "want " << where << "\n got " << message;
  EXPECT_NE(message.find(problem), std::string::npos)
      << "want …" << problem << "…\n got " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// A fresh folder for files a scenario refers to; removed by the destructor.
class TempFolder {
 public:
  explicit TempFolder(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("owsim_test_scenario_loader_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() { std::filesystem::remove_all(path_); }
  [[nodiscard]] std::filesystem::path write(const std::string& name,
                                            const std::string& text) const {
    std::ofstream(path_ / name) << text;
    return path_ / name;
  }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::string full(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// ---- the INTERFACE.md example ----

TEST(ScenarioLoader, InterfaceExampleLoadsEverySection) {
  const Scenario s = load_scenario_text(kInterfaceExample, "/x/example.yaml");
  EXPECT_EQ(s.name, "single_span");
  EXPECT_EQ(s.path, std::filesystem::path("/x/example.yaml"));
  EXPECT_EQ(s.seed, 42u);
  EXPECT_DOUBLE_EQ(s.origin.lat_deg, 48.6881);
  EXPECT_DOUBLE_EQ(s.origin.lon_deg, 10.8447);
  EXPECT_DOUBLE_EQ(s.origin.h_m, 450.0);

  EXPECT_EQ(s.scan.model, SensorModel::milows);
  EXPECT_DOUBLE_EQ(s.mount.pitch_deg, -4.0);
  EXPECT_DOUBLE_EQ(s.mount.roll_deg, 0.0);
  EXPECT_DOUBLE_EQ(s.mount.yaw_deg, 0.0);
  EXPECT_EQ(s.mount.lever_arm_m, Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(s.receiver.beam.divergence_mrad, 1.0);
  EXPECT_DOUBLE_EQ(s.receiver.threshold, 0.005);
  EXPECT_DOUBLE_EQ(s.receiver.range_noise_sigma_m, 0.4241);
  EXPECT_EQ(s.receiver.rule, ReturnRule::first_second);
  EXPECT_DOUBLE_EQ(s.receiver.atmosphere.transmission, 0.95);
  EXPECT_FALSE(s.receiver.atmosphere.visibility_km);

  const TrajectorySpec& t = s.trajectory;
  EXPECT_EQ(t.source, TrajectorySpec::Source::waypoints);
  EXPECT_DOUBLE_EQ(t.speed_mps, 40.0);
  ASSERT_EQ(t.waypoints_enu_m.size(), 2u);
  EXPECT_EQ(t.waypoints_enu_m[0], Eigen::Vector3d(-1200, 0, 100));
  EXPECT_EQ(t.waypoints_enu_m[1], Eigen::Vector3d(400, 0, 100));
  EXPECT_DOUBLE_EQ(t.max_bank_deg, 30.0);
  EXPECT_DOUBLE_EQ(t.start_s, 0.0);
  ASSERT_TRUE(t.duration_s);
  EXPECT_DOUBLE_EQ(*t.duration_s, 30.0);
  EXPECT_DOUBLE_EQ(s.scan.start_s, 0.0);

  const SceneSpec& scene = s.scene;
  EXPECT_EQ(scene.terrain.kind, TerrainKind::flat);
  EXPECT_DOUBLE_EQ(scene.terrain.flat_u_m, 0.0);
  ASSERT_EQ(scene.spans.size(), 1u);
  const SpanSpec& span = scene.spans[0];
  EXPECT_EQ(span.id, "line-a");
  EXPECT_EQ(span.from_en, Eigen::Vector2d(0, -200));
  EXPECT_EQ(span.to_en, Eigen::Vector2d(0, 200));
  EXPECT_DOUBLE_EQ(span.support_height_1_m, 30.0);
  EXPECT_DOUBLE_EQ(span.support_height_2_m, 30.0);
  EXPECT_DOUBLE_EQ(span.lowest_point_m, 20.0);
  ASSERT_EQ(span.offsets.size(), 1u);
  EXPECT_DOUBLE_EQ(span.offsets[0].lateral_m, 0.0);
  EXPECT_DOUBLE_EQ(span.conductor_diameter_m, 0.020);
  EXPECT_DOUBLE_EQ(span.conductor_reflectivity, 0.4);
  EXPECT_TRUE(span.support_poles);
  EXPECT_DOUBLE_EQ(span.pole_diameter_m, 0.5);
  EXPECT_DOUBLE_EQ(span.pole_reflectivity, 0.3);

  ASSERT_EQ(scene.poles.size(), 1u);
  EXPECT_EQ(scene.poles[0].id, "p1");
  EXPECT_EQ(scene.poles[0].surface, SurfaceClass::pole);
  EXPECT_EQ(scene.poles[0].base_enu_m, Eigen::Vector3d(50, 50, 0));
  EXPECT_DOUBLE_EQ(scene.poles[0].height_m, 25.0);
  EXPECT_DOUBLE_EQ(scene.poles[0].radius_m, 0.2);
  EXPECT_DOUBLE_EQ(scene.poles[0].reflectivity, 0.3);

  ASSERT_EQ(scene.trees.size(), 1u);
  const Cylinder& tree = scene.trees[0];
  EXPECT_EQ(tree.id, "t1");
  EXPECT_EQ(tree.surface, SurfaceClass::tree);
  EXPECT_NEAR(tree.base_enu_m.z(), 0.0, 1e-9);  // on the flat terrain
  const Geodetic back = LocalFrame(s.origin).geodetic_from_enu(tree.base_enu_m);
  EXPECT_NEAR(back.lat_deg, 48.689, 1e-10);
  EXPECT_NEAR(back.lon_deg, 10.846, 1e-10);
  // 0.0013° of longitude and 0.0009° of latitude on the WGS-84 radii of curvature at 48.69° N.
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double lat = 48.6885 * std::numbers::pi / 180.0, w = 1 - e2 * std::sin(lat) * std::sin(lat);
  const double prime_vertical_m = a / std::sqrt(w), meridian_m = a * (1 - e2) / std::pow(w, 1.5);
  EXPECT_NEAR(tree.base_enu_m.x(),
              0.0013 * std::numbers::pi / 180 * prime_vertical_m * std::cos(lat), 0.05);
  EXPECT_NEAR(tree.base_enu_m.y(), 0.0009 * std::numbers::pi / 180 * meridian_m, 0.05);
  EXPECT_DOUBLE_EQ(tree.height_m, 15.0);
  EXPECT_DOUBLE_EQ(tree.radius_m, 2.0);
  EXPECT_DOUBLE_EQ(tree.reflectivity, 0.2);

  ASSERT_TRUE(scene.forest);
  EXPECT_EQ(scene.forest->count, 0);
  EXPECT_EQ(scene.forest->e_range, Eigen::Vector2d(-500, 500));
  EXPECT_EQ(scene.forest->n_range, Eigen::Vector2d(-500, 500));
  EXPECT_DOUBLE_EQ(scene.forest->height_min_m, 8.0);
  EXPECT_DOUBLE_EQ(scene.forest->height_max_m, 25.0);
  EXPECT_DOUBLE_EQ(scene.forest->diameter_min_m, 2.0);
  EXPECT_DOUBLE_EQ(scene.forest->diameter_max_m, 8.0);

  const Scene built = build_scene(s);
  ASSERT_EQ(built.conductors.size(), 1u);
  EXPECT_EQ(built.conductors[0].id, "line-a/1");
  ASSERT_EQ(built.cylinders.size(), 4u);  // two span poles, p1, t1
  EXPECT_EQ(built.cylinders[2].id, "p1");
  EXPECT_EQ(built.cylinders[3].id, "t1");
}

TEST(ScenarioLoader, ExampleFileLoadsAndBuildsOneConductorAndTwoPoles) {
  const std::filesystem::path path =
      std::filesystem::path(OWSIM_SOURCE_DIR) / "examples" / "single_span.yaml";
  const Scenario s = load_scenario(path);
  EXPECT_EQ(s.name, "single_span");
  EXPECT_EQ(s.trajectory.source, TrajectorySpec::Source::waypoints);
  const Scene scene = build_scene(s);
  ASSERT_EQ(scene.conductors.size(), 1u);
  EXPECT_DOUBLE_EQ(scene.conductors[0].radius_m, 0.010);
  ASSERT_EQ(scene.cylinders.size(), 2u);
  for (const Cylinder& pole : scene.cylinders) EXPECT_EQ(pole.surface, SurfaceClass::pole);
  // Approached head-on: the route crosses the span at right angles.
  const Eigen::Vector3d route = s.trajectory.waypoints_enu_m[1] - s.trajectory.waypoints_enu_m[0];
  const Eigen::Vector2d along = s.scene.spans[0].to_en - s.scene.spans[0].from_en;
  EXPECT_NEAR(route.head<2>().dot(along), 0.0, 1e-9);
}

// ---- defaults ----

TEST(ScenarioLoader, MinimalScenarioHasTheSpecDefaults) {
  const Scenario s = load_scenario_text(kMinimal, "/a/b/minimal.yaml");
  EXPECT_EQ(s.name, "m");
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.scan.model, SensorModel::milows);
  EXPECT_DOUBLE_EQ(s.receiver.threshold, 0.0029);  // calibrated with the receiver noise (0.1.0: 0.005)
  EXPECT_DOUBLE_EQ(s.receiver.range_noise_sigma_m, 0.4241);
  EXPECT_DOUBLE_EQ(s.receiver.beam.divergence_mrad, 1.0);
  EXPECT_DOUBLE_EQ(s.receiver.beam.exit_radius_m, 0.0);
  EXPECT_EQ(s.receiver.rule, ReturnRule::first_second);
  EXPECT_DOUBLE_EQ(s.receiver.min_return_separation_m, 0.75);
  EXPECT_DOUBLE_EQ(s.receiver.atmosphere.transmission, 0.95);
  EXPECT_FALSE(s.receiver.atmosphere.visibility_km);
  EXPECT_DOUBLE_EQ(s.receiver.atmosphere.wavelength_um, 1.5);
  EXPECT_DOUBLE_EQ(s.scan.prf_hz, 61'111.0);
  EXPECT_EQ(s.scan.fibers_per_line, 128);
  EXPECT_EQ(s.scan.lines_per_frame, 159);
  EXPECT_EQ(s.scan.pulses_per_frame(), 20'352);
  EXPECT_DOUBLE_EQ(s.scan.sweep_deg, 36.0);
  EXPECT_DOUBLE_EQ(s.scan.sawtooth_deg, 0.134);
  EXPECT_DOUBLE_EQ(s.scan.frame_jitter_deg, 0.114248067);
  EXPECT_DOUBLE_EQ(s.scan.look_into_turn_s, 2.0);
  EXPECT_DOUBLE_EQ(s.scan.look_into_turn_limit_deg, 12.0);
  EXPECT_EQ(s.scan.fiber_order, FiberOrder::crosstalk_resorted);
  EXPECT_TRUE(s.scan.alpha_table_deg.empty());
  EXPECT_EQ(s.scan.reference_counts, 10);
  EXPECT_DOUBLE_EQ(s.scan.hellas_mirror_angle_factor_deg, 0.0);
  EXPECT_DOUBLE_EQ(s.scan.start_s, 0.0);
  for (const RangeCounterParams& counter : {s.scan.counter, s.receiver.counter}) {
    EXPECT_DOUBLE_EQ(counter.speed_of_light_mps, 299'792'500.0);
    EXPECT_DOUBLE_EQ(counter.refractive_index_air, 1.0003);
    EXPECT_DOUBLE_EQ(counter.timer_period_s, 4e-9);
    EXPECT_EQ(counter.timeout_counts, 2066);
    EXPECT_NEAR(range_per_count_m(counter), 0.59940, 1e-5);  // SENSOR-SPEC §1
  }
  EXPECT_DOUBLE_EQ(s.mount.roll_deg, 0.0);
  EXPECT_DOUBLE_EQ(s.mount.pitch_deg, 0.0);
  EXPECT_DOUBLE_EQ(s.trajectory.max_bank_deg, 30.0);
  EXPECT_FALSE(s.trajectory.irs_noise);
  EXPECT_DOUBLE_EQ(s.trajectory.start_s, 0.0);
  EXPECT_FALSE(s.trajectory.duration_s);
  EXPECT_EQ(s.scene.terrain.kind, TerrainKind::flat);
  EXPECT_DOUBLE_EQ(s.scene.terrain.flat_u_m, 0.0);
  EXPECT_DOUBLE_EQ(s.scene.terrain.reflectivity, 0.2);
  EXPECT_TRUE(s.scene.spans.empty());
  EXPECT_TRUE(s.scene.poles.empty());
  EXPECT_FALSE(s.scene.forest);

  // Without a name, the file's stem.
  const std::string unnamed = std::string(kMinimal).substr(std::string(kMinimal).find('\n') + 1);
  EXPECT_EQ(load_scenario_text(unnamed, "/a/b/night_flight.yaml").name, "night_flight");
}

TEST(ScenarioLoader, SpanDefaultsAndPoleTreeReflectivity) {
  const Scenario s = load_scenario_text(std::string(kMinimal) + R"(scene:
  spans:
    - {id: s, from: {e: 0, n: 0}, to: {e: 100, n: 0}}
  poles: [{id: p, at: {e: 1, n: 1}, height_m: 5, diameter_m: 1}]
  trees: [{id: t, at: {e: 2, n: 1}, height_m: 5, diameter_m: 1}]
)",
                                        kPath);
  const SpanSpec defaults;
  const SpanSpec& span = s.scene.spans.at(0);
  EXPECT_DOUBLE_EQ(span.support_height_1_m, defaults.support_height_1_m);
  EXPECT_DOUBLE_EQ(span.lowest_point_m, defaults.lowest_point_m);
  EXPECT_DOUBLE_EQ(span.conductor_diameter_m, 0.020);
  EXPECT_DOUBLE_EQ(span.conductor_reflectivity, 0.4);
  EXPECT_EQ(span.offsets.size(), 1u);
  EXPECT_DOUBLE_EQ(s.scene.poles.at(0).reflectivity, 0.3);
  EXPECT_DOUBLE_EQ(s.scene.trees.at(0).reflectivity, 0.2);
}

// ---- every key reaches its field ----

TEST(ScenarioLoader, EverySensorConstantCanBeOverridden) {
  std::string alpha = "[";
  for (int i = 0; i < 9; ++i) alpha += std::to_string(-20 + 5 * i) + (i < 8 ? ", " : "]");
  const Scenario s = load_scenario_text(std::string(kMinimal) + R"(  start_s: 2.5
seed: 18446744073709551615
sensor:
  model: hellas
  mount: {roll_deg: 1, pitch_deg: -2, yaw_deg: 3, lever_arm_m: [0.5, -0.25, 1]}
  divergence_mrad: 2.5
  beam_exit_radius_m: 0.01
  threshold: 0.02
  range_noise_sigma_m: 0
  returns: strongest
  min_return_separation_m: 1.5
  prf_hz: 50000
  fibers_per_line: 10
  lines_per_frame: 20
  sweep_deg: 30
  sawtooth_deg: 0.1
  frame_jitter_deg: 0.2
  look_into_turn_s: 0
  look_into_turn_limit_deg: 5
  fiber_order: sequential
  alpha_table_deg: )" + alpha + R"(
  reference_counts: 12
  hellas_mirror_angle_factor_deg: 0.002
  counter: {speed_of_light_mps: 299792458, refractive_index_air: 1.0, timer_period_s: 2e-9, timeout_counts: 4000}
atmosphere: {visibility_km: 5, wavelength_um: 1.55}
)",
                                        kPath);
  EXPECT_EQ(s.seed, 18446744073709551615ULL);
  EXPECT_EQ(s.scan.model, SensorModel::hellas);
  EXPECT_DOUBLE_EQ(s.mount.roll_deg, 1.0);
  EXPECT_DOUBLE_EQ(s.mount.pitch_deg, -2.0);
  EXPECT_DOUBLE_EQ(s.mount.yaw_deg, 3.0);
  EXPECT_EQ(s.mount.lever_arm_m, Eigen::Vector3d(0.5, -0.25, 1.0));
  EXPECT_DOUBLE_EQ(s.receiver.beam.divergence_mrad, 2.5);
  EXPECT_DOUBLE_EQ(s.receiver.beam.exit_radius_m, 0.01);
  EXPECT_DOUBLE_EQ(s.receiver.threshold, 0.02);
  EXPECT_DOUBLE_EQ(s.receiver.range_noise_sigma_m, 0.0);
  EXPECT_EQ(s.receiver.rule, ReturnRule::strongest);
  EXPECT_DOUBLE_EQ(s.receiver.min_return_separation_m, 1.5);
  EXPECT_DOUBLE_EQ(s.scan.prf_hz, 50'000.0);
  EXPECT_EQ(s.scan.fibers_per_line, 10);
  EXPECT_EQ(s.scan.lines_per_frame, 20);
  EXPECT_DOUBLE_EQ(s.scan.sweep_deg, 30.0);
  EXPECT_DOUBLE_EQ(s.scan.sawtooth_deg, 0.1);
  EXPECT_DOUBLE_EQ(s.scan.frame_jitter_deg, 0.2);
  EXPECT_DOUBLE_EQ(s.scan.look_into_turn_s, 0.0);
  EXPECT_DOUBLE_EQ(s.scan.look_into_turn_limit_deg, 5.0);
  EXPECT_EQ(s.scan.fiber_order, FiberOrder::sequential);
  ASSERT_EQ(s.scan.alpha_table_deg.size(), 9u);
  EXPECT_DOUBLE_EQ(s.scan.alpha_table_deg[8], 20.0);
  EXPECT_EQ(s.scan.reference_counts, 12);
  EXPECT_DOUBLE_EQ(s.scan.hellas_mirror_angle_factor_deg, 0.002);
  EXPECT_DOUBLE_EQ(s.scan.start_s, 2.5);  // trajectory.start_s
  for (const RangeCounterParams& counter : {s.scan.counter, s.receiver.counter}) {
    EXPECT_DOUBLE_EQ(counter.speed_of_light_mps, 299'792'458.0);
    EXPECT_DOUBLE_EQ(counter.refractive_index_air, 1.0);
    EXPECT_DOUBLE_EQ(counter.timer_period_s, 2e-9);
    EXPECT_EQ(counter.timeout_counts, 4000);
  }
  ASSERT_TRUE(s.receiver.atmosphere.visibility_km);
  EXPECT_DOUBLE_EQ(*s.receiver.atmosphere.visibility_km, 5.0);
  EXPECT_DOUBLE_EQ(s.receiver.atmosphere.wavelength_um, 1.55);
}

// ---- the receiver's statistics and the sun (SENSOR-SPEC §11) ----

TEST(ScenarioLoader, WithoutReceiverKeysNoiseIsOnWithItsDefaultsAndItIsNight) {
  const Scenario s = load_scenario_text(kMinimal, kPath);
  const ReceiverNoiseParams defaults;
  EXPECT_TRUE(s.receiver.noise.on);
  EXPECT_EQ(s.receiver.noise.noise_at_1km, defaults.noise_at_1km);
  EXPECT_EQ(s.receiver.noise.pulse_width_ns, defaults.pulse_width_ns);
  EXPECT_EQ(s.receiver.noise.sun_noise, defaults.sun_noise);
  EXPECT_EQ(s.receiver.noise.sky_noise, defaults.sky_noise);
  EXPECT_FALSE(s.receiver.sun.given);
}

TEST(ScenarioLoader, ReceiverStatisticsKeysLandInTheirFields) {
  const Scenario s = load_scenario_text(std::string(kMinimal) + R"(sensor:
  receiver:
    noise: off
    noise_at_1km: 0.002
    pulse_width_ns: 3.5
    sun_noise: 0.7
    sky_noise: 0.25
)",
                                        kPath);
  EXPECT_FALSE(s.receiver.noise.on);
  EXPECT_EQ(s.receiver.noise.noise_at_1km, 0.002);
  EXPECT_EQ(s.receiver.noise.pulse_width_ns, 3.5);
  EXPECT_EQ(s.receiver.noise.sun_noise, 0.7);
  EXPECT_EQ(s.receiver.noise.sky_noise, 0.25);
  // The switch as YAML 1.1 reads it (a boolean) or as text; either spelling, any case.
  for (const auto& [text, on] :
       {std::pair{"on", true}, std::pair{"off", false}, std::pair{"true", true},
        std::pair{"false", false}, std::pair{"On", true}, std::pair{"OFF", false},
        std::pair{"\"off\"", false}, std::pair{"'on'", true}}) {
    const Scenario switched = load_scenario_text(
        std::string(kMinimal) + "sensor: {receiver: {noise: " + text + "}}\n", kPath);
    EXPECT_EQ(switched.receiver.noise.on, on) << text;
  }
}

TEST(ScenarioLoader, TheSunFromItsAnglesOrFromATimeAtTheOrigin) {
  const Scenario angles = load_scenario_text(
      std::string(kMinimal) + "sun: {elevation_deg: 30, azimuth_deg: -45}\n", kPath);
  EXPECT_TRUE(angles.receiver.sun.given);
  EXPECT_EQ(angles.receiver.sun.elevation_deg, 30.0);
  EXPECT_EQ(angles.receiver.sun.azimuth_deg, 315.0);  // wrapped into [0, 360)
  EXPECT_EQ(load_scenario_text(std::string(kMinimal) + "sun: {elevation_deg: -90, azimuth_deg: "
                                                       "1000}\n",
                               kPath)
                .receiver.sun.azimuth_deg,
            280.0);

  // A time: the sun at the origin (48.6881 N, 10.8447 E); astral puts it at 63.00°, 154.88°
  // (tests/test_solar_position.cpp compares the two over many times and places).
  const SunPosition expected =
      solar_position(parse_utc_time("2026-06-21T10:30:00Z"), 48.6881, 10.8447);
  for (const char* written : {"\"2026-06-21T10:30:00Z\"", "2026-06-21T10:30:00Z"}) {
    const Scenario timed =
        load_scenario_text(std::string(kMinimal) + "sun: {time_utc: " + written + "}\n", kPath);
    EXPECT_TRUE(timed.receiver.sun.given);
    EXPECT_EQ(timed.receiver.sun.elevation_deg, expected.elevation_deg) << written;
    EXPECT_EQ(timed.receiver.sun.azimuth_deg, expected.azimuth_deg) << written;
  }
  EXPECT_NEAR(expected.elevation_deg, 63.00, 0.1);
  EXPECT_NEAR(expected.azimuth_deg, 154.88, 0.1);
  // The same instant seen from the other side of the Earth: the origin decides.
  std::string sydney = kMinimal;
  sydney.replace(sydney.find("lat: 48.6881, lon: 10.8447"), 26, "lat: -33.8688, lon: 151.2093");
  const Scenario south =
      load_scenario_text(sydney + "sun: {time_utc: \"2026-06-21T22:30:00Z\"}\n", kPath);
  EXPECT_NEAR(south.receiver.sun.elevation_deg, 14.50, 0.1);  // astral: 14.499°, 48.141°
  EXPECT_NEAR(south.receiver.sun.azimuth_deg, 48.14, 0.1);
}

TEST(ScenarioLoader, TrajectoryFileAndItsOptions) {
  const TempFolder folder("trajectory");
  (void)folder.write("flight.txt", "Pic # Time-Tag Heading\n");
  (void)folder.write("track.csv", "time_s\n");
  const std::filesystem::path scenario = folder.path() / "s.yaml";
  const std::string head = "origin: {lat: 48.6881, lon: 10.8447, h: 450}\n";
  const Scenario s = load_scenario_text(head + R"(trajectory:
  file: flight.txt
  tick_s: 0.001
  heading: magnetic
  magnetic_variation_deg: 2.5
  smoothing: {window: 11, degree: 2}
  irs_noise: true
  start_s: 10
  duration_s: 60
)",
                                        scenario);
  const TrajectorySpec& t = s.trajectory;
  EXPECT_EQ(t.source, TrajectorySpec::Source::file);
  EXPECT_EQ(t.file, folder.path() / "flight.txt");  // relative to the scenario's folder
  EXPECT_EQ(t.format, "hellsim");
  EXPECT_DOUBLE_EQ(t.tick_s, 0.001);
  EXPECT_TRUE(t.heading_magnetic);
  EXPECT_DOUBLE_EQ(t.magnetic_variation_deg, 2.5);
  EXPECT_EQ(t.smoothing_window, 11);
  EXPECT_EQ(t.smoothing_degree, 2);
  EXPECT_TRUE(t.irs_noise);
  EXPECT_DOUBLE_EQ(t.start_s, 10.0);
  EXPECT_DOUBLE_EQ(*t.duration_s, 60.0);
  EXPECT_DOUBLE_EQ(s.scan.start_s, 10.0);

  const Scenario csv =
      load_scenario_text(head + "trajectory: {file: track.csv, heading: true}\n", scenario);
  EXPECT_EQ(csv.trajectory.format, "csv");  // from the extension
  EXPECT_FALSE(csv.trajectory.heading_magnetic);
  EXPECT_EQ(csv.trajectory.smoothing_window, 9);
  EXPECT_EQ(csv.trajectory.smoothing_degree, 3);
  const Scenario sbet = load_scenario_text(
      head + "trajectory: {file: " + (folder.path() / "flight.txt").string() + ", format: sbet}\n",
      scenario);
  EXPECT_EQ(sbet.trajectory.format, "sbet");
  EXPECT_EQ(sbet.trajectory.file, folder.path() / "flight.txt");  // absolute, in its folder tree
}

TEST(ScenarioLoader, TerrainForms) {
  const TempFolder folder("terrain");
  // 3 × 3 samples 100 m apart, centres from (−100, −100) to (100, 100); heights rise to the east.
  (void)folder.write("dem.asc",
                     "ncols 3\nnrows 3\nxllcenter -100\nyllcenter -100\ncellsize 100\n"
                     "10 20 30\n10 20 30\n10 20 30\n");
  const std::filesystem::path scenario = folder.path() / "s.yaml";
  const Scenario grid = load_scenario_text(std::string(kMinimal) + R"(scene:
  terrain: {grid: dem.asc, reflectivity: 0.35}
  poles:
    - {id: p, at: {e: 50, n: 0}, height_m: 10, diameter_m: 1}
    - {id: q, at: {e: 50, n: 0, u: 100}, height_m: 10, diameter_m: 1}
  trees:
    - {id: t, at: {lat: 48.6885, lon: 10.8450}, height_m: 10, diameter_m: 1}
)",
                                           scenario);
  EXPECT_EQ(grid.scene.terrain.kind, TerrainKind::grid);
  EXPECT_DOUBLE_EQ(grid.scene.terrain.reflectivity, 0.35);
  EXPECT_EQ(grid.scene.terrain.grid.ncols, 3);
  EXPECT_NEAR(grid.scene.poles[0].base_enu_m.z(), 25.0, 1e-12);  // on the ground
  EXPECT_DOUBLE_EQ(grid.scene.poles[1].base_enu_m.z(), 100.0);   // as given
  const Eigen::Vector3d tree = grid.scene.trees[0].base_enu_m;
  EXPECT_NEAR(tree.z(), 20.0 + 0.1 * tree.x(), 1e-9);  // the lat/lon point lies on the terrain
  const Geodetic back = LocalFrame(grid.origin).geodetic_from_enu(tree);
  EXPECT_NEAR(back.lat_deg, 48.6885, 1e-10);
  EXPECT_NEAR(back.lon_deg, 10.8450, 1e-10);

  for (const char* none : {"none", "~"}) {
    const Scenario s =
        load_scenario_text(std::string(kMinimal) + "scene:\n  terrain: " + none + "\n", kPath);
    EXPECT_EQ(s.scene.terrain.kind, TerrainKind::none) << none;
  }
  const Scenario flat =
      load_scenario_text(std::string(kMinimal) + "scene: {terrain: {flat_u: -3.5}}\n", kPath);
  EXPECT_EQ(flat.scene.terrain.kind, TerrainKind::flat);
  EXPECT_DOUBLE_EQ(flat.scene.terrain.flat_u_m, -3.5);
}

TEST(ScenarioLoader, LayoutsAndSupports) {
  const Scenario s = load_scenario_text(std::string(kMinimal) + R"(scene:
  spans:
    - {id: a, from: {e: 0, n: 0}, to: {e: 200, n: 0}, layout: tri}
    - {id: b, from: {e: 0, n: 50}, to: {e: 200, n: 50}, layout: sept, support_heights_m: [40, 45],
       lowest_point_m: 30}
    - {id: c, from: {e: 0, n: 90}, to: {e: 200, n: 90}, layout: [[-2, 0], [2, -1.5]],
       supports: {kind: none}}
)",
                                        kPath);
  ASSERT_EQ(s.scene.spans.size(), 3u);
  EXPECT_EQ(s.scene.spans[0].offsets.size(), 3u);
  EXPECT_EQ(s.scene.spans[1].offsets.size(), 7u);
  ASSERT_EQ(s.scene.spans[2].offsets.size(), 2u);
  EXPECT_DOUBLE_EQ(s.scene.spans[2].offsets[1].lateral_m, 2.0);
  EXPECT_DOUBLE_EQ(s.scene.spans[2].offsets[1].vertical_m, -1.5);
  EXPECT_FALSE(s.scene.spans[2].support_poles);
  EXPECT_DOUBLE_EQ(s.scene.spans[1].support_height_2_m, 45.0);
}

// ---- positions: three forms, one point ----

TEST(ScenarioLoader, ThreePositionFormsAgreeWithPyproj) {
  // Where is the point 500 m east of the origin (u = 0) in WGS-84 and UTM 32N? pyproj: ECEF by
  // the rotation of the local tangent plane, then geodetic, then UTM (PROJ's own algorithms).
  const std::string oracle = run_python(
      "import numpy as np\n"
      "from pyproj import Transformer\n"
      "lat0, lon0, h0 = 48.6881, 10.8447, 450.0\n"
      "ecef = Transformer.from_crs('EPSG:4979', 'EPSG:4978', always_xy=True)\n"
      "geo = Transformer.from_crs('EPSG:4978', 'EPSG:4979', always_xy=True)\n"
      "utm = Transformer.from_crs('EPSG:4326', 'EPSG:32632', always_xy=True)\n"
      "f, l = np.radians(lat0), np.radians(lon0)\n"
      "R = np.array([[-np.sin(l), np.cos(l), 0],\n"
      "              [-np.sin(f)*np.cos(l), -np.sin(f)*np.sin(l), np.cos(f)],\n"
      "              [np.cos(f)*np.cos(l), np.cos(f)*np.sin(l), np.sin(f)]])\n"
      "p = np.array(ecef.transform(lon0, lat0, h0)) + R.T @ np.array([500.0, 0.0, 0.0])\n"
      "lon, lat, h = geo.transform(*p)\n"
      "E, N = utm.transform(lon, lat)\n"
      "print('%.17g %.17g %.17g %.17g %.17g' % (lat, lon, h, E, N))\n");
  std::istringstream values(oracle);
  double lat = 0, lon = 0, h = 0, easting = 0, northing = 0;
  ASSERT_TRUE(values >> lat >> lon >> h >> easting >> northing) << oracle;
  const std::string geo = "{lat: " + full(lat) + ", lon: " + full(lon);
  const std::string utm = "{utm: \"32n " + full(easting) + " " + full(northing) + "\"";
  const std::string utm_band = "{utm: \"32U " + full(easting) + " " + full(northing) + "\"";
  const std::string pole = ", height_m: 10, diameter_m: 1}\n";
  const Scenario s = load_scenario_text(R"(origin: {lat: 48.6881, lon: 10.8447, h: 450}
trajectory:
  waypoints:
    speed_mps: 40
    points:
      - )" + geo + ", h: " + full(h) + R"(}
      - {e: 500, n: 100, u: 0}
      - )" + utm + ", h: " + full(h) + R"(}
scene:
  terrain: {flat_u: 0}
  spans:
    - {id: s, from: )" + utm_band + R"(}, to: {e: 500, n: 400}}
  poles:
    - {id: enu, at: {e: 500, n: 0, u: 0})" + pole +
                                            "    - {id: geo, at: " + geo + ", h: " + full(h) + "}" +
                                            pole + "    - {id: utm, at: " + utm +
                                            ", h: " + full(h) + "}" + pole +
                                            "    - {id: geo-ground, at: " + geo + "}" + pole +
                                            "    - {id: utm-ground, at: " + utm_band + "}" + pole,
                                        kPath);
  const Eigen::Vector3d expected(500.0, 0.0, 0.0);
  ASSERT_EQ(s.scene.poles.size(), 5u);
  for (const Cylinder& p : s.scene.poles) {
    EXPECT_LT((p.base_enu_m - expected).norm(), 1e-3) << p.id << ": " << p.base_enu_m.transpose();
  }
  EXPECT_LT((s.trajectory.waypoints_enu_m[0] - expected).norm(), 1e-3);
  EXPECT_LT((s.trajectory.waypoints_enu_m[2] - expected).norm(), 1e-3);
  EXPECT_LT((s.scene.spans[0].from_en - expected.head<2>()).norm(), 1e-3);
}

// ---- errors: file, line, key path, problem ----

TEST(ScenarioLoaderErrors, MalformedYaml) {
  const std::string message = error_of("name: x\nsensor:\n  threshold: 0.1\n bad: 1\n");
  EXPECT_EQ(message.rfind(kPath.string() + ":4: malformed YAML: ", 0), 0u) << message;
  const std::string unclosed = error_of(std::string(kMinimal) + "sensor: {threshold: 0.1\n");
  EXPECT_EQ(unclosed.rfind(kPath.string() + ":", 0), 0u) << unclosed;
  EXPECT_NE(unclosed.find(": malformed YAML: "), std::string::npos) << unclosed;
}

TEST(ScenarioLoaderErrors, UnknownKeysAtAnyDepth) {
  const std::string m = kMinimal;
  expect_error(m + "sensr: {}\n", 7, "sensr",
               "unknown key 'sensr' in the file (did you mean 'sensor'?)");
  expect_error(m + "sensor:\n  treshold: 0.1\n", 8, "sensor.treshold",
               "unknown key 'treshold' in sensor (did you mean 'threshold'?)");
  expect_error(m + "sensor:\n  start_s: 1\n", 8, "sensor.start_s",
               "unknown key 'start_s' in sensor");
  expect_error(m + "sensor:\n  counter: {timeout: 100}\n", 8, "sensor.counter.timeout",
               "unknown key 'timeout' in sensor.counter");
  expect_error(m + "sensor:\n  mount: {pitch: -4}\n", 8, "sensor.mount.pitch",
               "unknown key 'pitch' in sensor.mount");
  expect_error(
      m + R"(scene:
  spans:
    - id: a
      from: {e: 0, n: 0}
      to: {e: 100, n: 0}
    - id: b
      from: {e: 0, n: 10}
      to: {e: 100, n: 10}
      conductor:
        diamter_mm: 20
)",
      16, "scene.spans[1].conductor.diamter_mm",
      "unknown key 'diamter_mm' in scene.spans[1].conductor (did you mean 'diameter_mm'?)");
  expect_error(
      m + "scene:\n  poles:\n    - {id: p, at: {e: 1, n: 2, x: 3}, height_m: 5, diameter_m: 1}\n",
      9, "scene.poles[0].at.x", "unknown key 'x' in scene.poles[0].at");
  expect_error(m + "    max_bank: 20\n", 7, "trajectory.waypoints.max_bank",
               "did you mean 'max_bank_deg'?");
  expect_error(m + "  duration: 5\n", 7, "trajectory.duration", "did you mean 'duration_s'?");
  expect_error(m + "atmosphere: {transmision: 0.9}\n", 7, "atmosphere.transmision",
               "did you mean 'transmission'?");
  expect_error(m + "scene: {forest: {count: 1, area: {x: [0, 1]}}}\n", 7, "scene.forest.area.x",
               "unknown key 'x' in scene.forest.area");
}

TEST(ScenarioLoaderErrors, WrongTypes) {
  const std::string m = kMinimal;
  expect_error(m + "sensor:\n  threshold: abc\n", 8, "sensor.threshold",
               "expected a number, got 'abc'");
  expect_error(m + "sensor:\n  fibers_per_line: 12.5\n", 8, "sensor.fibers_per_line",
               "expected an integer, got '12.5'");
  expect_error(m + "sensor:\n  alpha_table_deg: 5\n", 8, "sensor.alpha_table_deg",
               "expected a list [...], got '5'");
  expect_error(m + "sensor:\n  mount: {lever_arm_m: [1, 2]}\n", 8, "sensor.mount.lever_arm_m",
               "expected a list of 3 numbers, got a list of 2");
  expect_error(m + "sensor: fast\n", 7, "sensor",
               "expected a mapping {key: value, ...}, got 'fast'");
  expect_error(m + "seed: -1\n", 7, "seed", "expected a non-negative integer, got '-1'");
  expect_error(m + "  irs_noise: maybe\n", 7, "trajectory.irs_noise",
               "expected true or false, got 'maybe'");
  expect_error(m + "scene:\n  spans: {id: a}\n", 8, "scene.spans",
               "expected a list [...], got a mapping");
}

TEST(ScenarioLoaderErrors, MissingRequiredKeys) {
  const std::string m = kMinimal;
  expect_error("name: x\ntrajectory: {}\n", 1, "origin", "required, but missing from the file");
  expect_error("origin: {lat: 48, lon: 10, h: 0}\n", 1, "trajectory",
               "required, but missing from the file");
  expect_error("origin: {lat: 48, lon: 10}\ntrajectory: {}\n", 1, "origin.h",
               "required, but missing from origin");
  expect_error("origin: {lat: 48, lon: 10, h: 0}\ntrajectory: {start_s: 0}\n", 2, "trajectory",
               "needs a source: waypoints or file");
  expect_error(R"(origin: {lat: 48, lon: 10, h: 0}
trajectory:
  waypoints:
    points: [{e: 0, n: 0, u: 100}, {e: 100, n: 0, u: 100}]
)",
               3, "trajectory.waypoints.speed_mps",
               "required, but missing from trajectory.waypoints");
  expect_error(m + "scene:\n  spans:\n    - {from: {e: 0, n: 0}, to: {e: 1, n: 0}}\n", 9,
               "scene.spans[0].id", "required, but missing from scene.spans[0]");
  expect_error(R"(origin: {lat: 48, lon: 10, h: 0}
trajectory:
  waypoints:
    speed_mps: 40
    points:
      - {e: 0, n: 0, u: 100}
      - {e: 100, n: 0}
)",
               7, "trajectory.waypoints.points[1].u",
               "required, but missing from trajectory.waypoints.points[1]");
  expect_error(R"(origin: {lat: 48, lon: 10, h: 0}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: 0, n: 0, u: 100}]
)",
               5, "trajectory.waypoints.points", "at least 2 waypoints, got 1");
  expect_error(m + "scene:\n  poles:\n    - {id: p, height_m: 5, diameter_m: 1}\n", 9,
               "scene.poles[0].at", "required");
}

TEST(ScenarioLoaderErrors, NonFiniteAndNegativeSizes) {
  const std::string m = kMinimal;
  expect_error(m + "sensor:\n  threshold: .nan\n", 8, "sensor.threshold", "expected a number");
  expect_error(m + "sensor:\n  prf_hz: inf\n", 8, "sensor.prf_hz", "expected a finite number");
  expect_error(m + "sensor:\n  prf_hz: -5\n", 8, "sensor.prf_hz",
               "must be in [1, 1000000] Hz, got -5");
  expect_error(
      m + "scene:\n  poles:\n    - {id: p, at: {e: 1, n: 1}, height_m: 5, diameter_m: -1}\n", 9,
      "scene.poles[0].diameter_m", "must be in [0.001, 20] m, got -1");
  expect_error(
      m + "scene:\n  trees:\n    - {id: t, at: {e: 1, n: 1}, height_m: 0, diameter_m: 1}\n", 9,
      "scene.trees[0].height_m", "must be > 0, got 0");
  expect_error(m + R"(scene:
  spans:
    - id: a
      from: {e: 0, n: 0}
      to: {e: 100, n: 0}
      conductor: {diameter_mm: -20}
)",
               12, "scene.spans[0].conductor.diameter_mm", "must be in [1, 200] mm, got -20");
  expect_error(m + "  duration_s: -3\n", 7, "trajectory.duration_s",
               "must be in [0, 86400] s, got -3");
  expect_error(m + "  start_s: -1\n", 7, "trajectory.start_s", "must be in [0, 1e+10] s, got -1");
  expect_error(m + "    speed_mps: 50\n", 7, "trajectory.waypoints.speed_mps",
               "key 'speed_mps' given twice in trajectory.waypoints (first at line 5)");
  expect_error(R"(origin: {lat: 48, lon: 10, h: 0}
trajectory:
  waypoints:
    speed_mps: 0
    points: [{e: 0, n: 0, u: 100}, {e: 100, n: 0, u: 100}]
)",
               4, "trajectory.waypoints.speed_mps", "must be in [1, 150] m/s, got 0");
  expect_error(m + "scene:\n  forest: {count: 5, height_m: [25, 8]}\n", 8, "scene.forest.height_m",
               "must be a finite range [min, max] with min ≤ max, got [25, 8]");
  expect_error(m + "scene:\n  forest: {count: -1}\n", 8, "scene.forest.count",
               "must be in [0, 1000000], got -1");
  expect_error(m + "scene:\n  terrain: {flat_u: 0, reflectivity: 1.5}\n", 8,
               "scene.terrain.reflectivity", "must be in [0, 1], got 1.5");
}

TEST(ScenarioLoaderErrors, ReceiverStatisticsAndSun) {
  const std::string m = kMinimal;
  const std::string r = m + "sensor:\n  receiver: ";
  expect_error(r + "{noise_at_1km: -0.001}\n", 8, "sensor.receiver.noise_at_1km",
               "must be in [0, 1], got -0.001");
  expect_error(r + "{noise_at_1km: .nan}\n", 8, "sensor.receiver.noise_at_1km",
               "expected a number");
  expect_error(r + "{sun_noise: -1}\n", 8, "sensor.receiver.sun_noise",
               "must be in [0, 1000], got -1");
  expect_error(r + "{sky_noise: -0.5}\n", 8, "sensor.receiver.sky_noise",
               "must be in [0, 1000], got -0.5");
  expect_error(r + "{sky_noise: inf}\n", 8, "sensor.receiver.sky_noise",
               "expected a finite number");
  expect_error(r + "{pulse_width_ns: 0}\n", 8, "sensor.receiver.pulse_width_ns",
               "must be in [0.1, 1000] ns, got 0");
  expect_error(r + "{pulse_width_ns: -5}\n", 8, "sensor.receiver.pulse_width_ns",
               "must be in [0.1, 1000] ns, got -5");
  expect_error(r + "{noise: maybe}\n", 8, "sensor.receiver.noise",
               "expected on or off, got 'maybe'");
  expect_error(r + "{nois: off}\n", 8, "sensor.receiver.nois",
               "unknown key 'nois' in sensor.receiver (did you mean 'noise'?)");

  expect_error(m + "sun: {elevation_deg: 200, azimuth_deg: 0}\n", 7, "sun.elevation_deg",
               "must be in [-90, 90] deg, got 200");
  expect_error(m + "sun: {elevation_deg: 10, azimuth_deg: -inf}\n", 7, "sun.azimuth_deg",
               "expected a finite number");
  expect_error(m + "sun: {elevation_deg: 10}\n", 7, "sun.azimuth_deg", "required, but missing");
  expect_error(m + "sun: {elevation: 10, azimuth_deg: 0}\n", 7, "sun.elevation",
               "unknown key 'elevation' in sun (did you mean 'elevation_deg'?)");
  expect_error(m + "sun: {}\n", 7, "sun", "needs {elevation_deg, azimuth_deg} or {time_utc:");
  expect_error(m + "sun: {time_utc: tomorrow}\n", 7, "sun.time_utc",
               "expected an ISO 8601 UTC time like 2026-06-21T10:30:00Z, got 'tomorrow'");
  expect_error(m + "sun: {time_utc: \"2026-02-30T10:00:00Z\"}\n", 7, "sun.time_utc",
               "no day 30 in that month: '2026-02-30T10:00:00Z'");
  expect_error(m + "sun: {time_utc: \"2026-06-21T12:30:00+02:00\"}\n", 7, "sun.time_utc",
               "must be a UTC time (ending in Z), got the offset +02:00");
  expect_error(m + "sun:\n  time_utc: \"2026-06-21T10:30:00Z\"\n  elevation_deg: 45\n", 8,
               "sun.time_utc", "give time_utc or elevation_deg and azimuth_deg, not both");
}

TEST(ScenarioLoaderErrors, ImpossibleValues) {
  const std::string m = kMinimal;
  // A sag above its supports: caught at load by build_span, at the key's line.
  expect_error(m + R"(scene:
  spans:
    - id: a
      from: {e: 0, n: 0}
      to: {e: 100, n: 0}
      support_heights_m: [30, 30]
      lowest_point_m: 40
)",
               13, "scene.spans[0].lowest_point_m", "40 m is above a support");
  // A defaulted key that fails: the span's own line.
  expect_error(m + R"(scene:
  spans:
    - id: a
      from: {e: 0, n: 0}
      to: {e: 100, n: 0}
      support_heights_m: [10, 10]
)",
               9, "scene.spans[0].lowest_point_m", "20 m is above a support");
  expect_error(m + "scene:\n  spans:\n    - {id: a, from: {e: 5, n: 5}, to: {e: 5, n: 5}}\n", 9,
               "scene.spans[0].to", "the two supports stand at the same place");
  expect_error(m + "sensor:\n  threshold: 1.5\n", 8, "sensor.threshold",
               "must be in [0, 1], got 1.5");
  expect_error(m + "sensor:\n  model: milos\n", 8, "sensor.model",
               "expected one of milows | hellas, got 'milos'");
  expect_error(m + "sensor:\n  returns: last\n", 8, "sensor.returns",
               "expected one of first_second | strongest, got 'last'");
  expect_error(m + "sensor:\n  sweep_deg: 70\n", 8, "sensor.sweep_deg", "leaves the mirror's");
  expect_error(m + "sensor:\n  frame_jitter_deg: 20\n", 7, "sensor.sweep_deg",
               "leaves the mirror's");  // the defaulted sweep: the section's line
  expect_error(m + "sensor:\n  alpha_table_deg: [1, 2]\n", 8, "sensor.alpha_table_deg",
               "holds 2 angles");
  expect_error(m + "sensor:\n  counter:\n    speed_of_light_mps: -1\n", 9,
               "sensor.counter.speed_of_light_mps",
               "must be in [290000000, 300000000] m/s, got -1");
  expect_error(m + "sensor:\n  counter: {timeout_counts: 5000}\n", 8,
               "sensor.counter.timeout_counts", "must be an integer in [1, 4095], got 5000");
  expect_error(m + "sensor:\n  reference_counts: 4096\n", 8, "sensor.reference_counts",
               "must be an integer in [0, 4095]");
  expect_error(m + "atmosphere: {transmission: 1.5}\n", 7, "atmosphere.transmission",
               "must be in [0, 1], got 1.5");
  expect_error(m + "atmosphere: {transmission: 0.9, visibility_km: 5}\n", 7,
               "atmosphere.visibility_km", "give transmission or visibility_km, not both");
  expect_error(m + "atmosphere: {visibility_km: -5}\n", 7, "atmosphere.visibility_km",
               "must be in [0.001, 1000] km, got -5");
  expect_error("name: x\norigin: {lat: 91, lon: 10, h: 0}\ntrajectory: {}\n", 2, "origin.lat",
               "must be in [-90, 90] deg, got 91");
  expect_error("name: a/b\n" + m.substr(m.find('\n') + 1), 1, "name", "without '/'");
  expect_error(m + "    max_bank_deg: 90\n", 7, "trajectory.waypoints.max_bank_deg",
               "must be in [1, 60] deg, got 90");
  expect_error(R"(origin: {lat: 48, lon: 10, h: 0}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: 0, n: 0, u: 100}, {e: 0, n: 0, u: 100}]
)",
               5, "trajectory.waypoints.points[1]", "repeats the previous waypoint");
}

TEST(ScenarioLoaderErrors, TrajectorySources) {
  const TempFolder folder("sources");
  (void)folder.write("f.txt", "x\n");
  const std::filesystem::path scenario = folder.path() / "s.yaml";
  const auto error_at = [&](const std::string& yaml) { return error_of(yaml, scenario); };
  const std::string where = scenario.string() + ":";
  const std::string head = "origin: {lat: 48, lon: 10, h: 0}\ntrajectory:\n";
  const std::string waypoints =
      "  waypoints: {speed_mps: 40, points: [{e: 0, n: 0, u: 1}, {e: 9, n: 0, u: 1}]}\n";
  EXPECT_EQ(error_at(head + waypoints + "  file: f.txt\n"),
            where +
                "4: trajectory.file: a trajectory has exactly one source: give waypoints or "
                "file, not both");
  EXPECT_EQ(error_at(head + waypoints + "  tick_s: 0.001\n"),
            where + "4: trajectory.tick_s: applies only to a trajectory file");
  EXPECT_EQ(error_at(head + "  file: missing.txt\n"), where + "3: trajectory.file: no such file: " +
                                                          (folder.path() / "missing.txt").string());
  EXPECT_EQ(error_at(head + "  file: f.txt\n  heading: magnetic\n"),
            where +
                "4: trajectory.heading: heading: magnetic needs magnetic_variation_deg (true = "
                "magnetic + variation)");
  EXPECT_EQ(error_at(head + "  file: f.txt\n  magnetic_variation_deg: 2\n"),
            where + "4: trajectory.magnetic_variation_deg: applies only with heading: magnetic");
  EXPECT_EQ(
      error_at(head + "  file: f.txt\n  format: gpx\n"),
      where + "4: trajectory.format: expected one of hellsim | csv | sbet | ardupilot, got 'gpx'");
  EXPECT_EQ(error_at(head + "  file: f.txt\n  format: csv\n  tick_s: 0.1\n"),
            where + "5: trajectory.tick_s: applies only to format hellsim");
  EXPECT_EQ(error_at(head + "  file: f.txt\n  smoothing: {window: 8}\n"),
            where + "4: trajectory.smoothing.window: a Savitzky–Golay window must be odd, got 8");
  EXPECT_EQ(error_at(head + "  file: f.txt\n  smoothing: {window: 5, degree: 5}\n"),
            where + "4: trajectory.smoothing.degree: the degree (5) must be below the window (5)");
}

TEST(ScenarioLoaderErrors, DuplicateAndReservedIds) {
  const std::string m = kMinimal;
  expect_error(m + R"(scene:
  poles:
    - {id: x, at: {e: 1, n: 1}, height_m: 5, diameter_m: 1}
  trees:
    - {id: x, at: {e: 2, n: 2}, height_m: 5, diameter_m: 1}
)",
               11, "scene.trees[0].id", "duplicate id 'x' (first used at line 9)");
  expect_error(m + R"(scene:
  spans:
    - {id: line, from: {e: 0, n: 0}, to: {e: 100, n: 0}}
    - {id: line, from: {e: 0, n: 9}, to: {e: 100, n: 9}}
)",
               10, "scene.spans[1].id", "duplicate id 'line'");
  expect_error(m + "scene:\n  poles: [{id: a/1, at: {e: 1, n: 1}, height_m: 5, diameter_m: 1}]\n",
               8, "scene.poles[0].id", "'/' is reserved");
  expect_error(
      m + "scene:\n  poles:\n    - {id: p, id: q, at: {e: 1, n: 1}, height_m: 5, diameter_m: 1}\n",
      9, "scene.poles[0].id", "key 'id' given twice in scene.poles[0]");
}

TEST(ScenarioLoaderErrors, Positions) {
  const std::string m = kMinimal;
  const std::string tail = ", height_m: 5, diameter_m: 1}\n";
  expect_error(m + "scene:\n  poles:\n    - {id: p, at: {e: 1, n: 2, lat: 48, lon: 10}" + tail, 9,
               "scene.poles[0].at", "mixes the {e, n, u} and {lat, lon, h} forms of a position");
  expect_error(
      m + "scene:\n  poles:\n    - {id: p, at: {utm: \"32U 634000 5394000\", lat: 48}" + tail, 9,
      "scene.poles[0].at", "mixes the {lat, lon, h} and {utm, h} forms");
  expect_error(m + "scene:\n  poles:\n    - {id: p, at: {e: 1, n: 2, h: 3}" + tail, 9,
               "scene.poles[0].at", "mixes the {e, n, u} form with h");
  expect_error(m + "scene:\n  poles:\n    - {id: p, at: {h: 3}" + tail, 9, "scene.poles[0].at",
               "expected a position {e, n, u}, {lat, lon, h} or {utm:");
  expect_error(m + "scene:\n  poles:\n    - {id: p, at: {utm: \"99Q 1 2\"}" + tail, 9,
               "scene.poles[0].at.utm", "UTM position \"99Q 1 2\"");
  expect_error(m + "scene:\n  poles:\n    - {id: p, at: {lat: 95, lon: 10}" + tail, 9,
               "scene.poles[0].at.lat", "must be in [-90, 90] deg, got 95");
  expect_error(m + "scene:\n  poles:\n    - {id: p, at: {e: 1}" + tail, 9, "scene.poles[0].at.n",
               "required, but missing from scene.poles[0].at");
  expect_error(m + "scene:\n  spans:\n    - {id: s, from: {e: 0, n: 0, u: 5}, to: {e: 9, n: 0}}\n",
               9, "scene.spans[0].from.u", "a span support stands on the terrain");
}

TEST(ScenarioLoaderErrors, TerrainFiles) {
  const TempFolder folder("grid");
  (void)folder.write("dem.asc",
                     "ncols 2\nnrows 2\nxllcenter 0\nyllcenter 0\ncellsize 10\n1 2\n3 4\n");
  (void)folder.write("bad.asc",
                     "ncols 2\nnrows 2\nxllcenter 0\nyllcenter 0\ncellsiz 10\n1 2\n3 4\n");
  const std::filesystem::path scenario = folder.path() / "s.yaml";
  const std::string where = scenario.string() + ":";
  const std::string m = kMinimal;
  EXPECT_EQ(
      error_of(m + "scene:\n  terrain: {grid: nothere.asc}\n", scenario),
      where + "8: scene.terrain.grid: no such file: " + (folder.path() / "nothere.asc").string());
  EXPECT_EQ(error_of(m + "scene:\n  terrain: {grid: bad.asc}\n", scenario),
            where + "8: scene.terrain.grid: " + (folder.path() / "bad.asc").string() +
                ":5: unknown header key 'cellsiz'");
  const std::string off =
      error_of(m + "scene:\n  terrain: {grid: dem.asc}\n  poles:\n    - {id: p, at: {e: 50, n: 5}, "
                   "height_m: 5, diameter_m: 1}\n",
               scenario);
  EXPECT_EQ(off.rfind(where + "10: scene.poles[0].at: terrain grid: point (e 50, n 5)", 0), 0u)
      << off;
  const std::string span_off = error_of(
      m + "scene:\n  terrain: {grid: dem.asc}\n  spans:\n    - id: s\n      from: {e: 5, n: 5}\n"
          "      to: {e: 50, n: 5}\n",
      scenario);
  EXPECT_EQ(span_off.rfind(where + "12: scene.spans[0].to: terrain grid:", 0), 0u) << span_off;
  const std::string forest_off = error_of(
      m + "scene:\n  terrain: {grid: dem.asc}\n  forest:\n    count: 3\n    area: {e: [0, 50], n: "
          "[0, 10]}\n",
      scenario);
  EXPECT_EQ(forest_off.rfind(where + "11: scene.forest.area: tree ", 0), 0u) << forest_off;
  expect_error(m + "scene:\n  terrain: {flat_u: 0, grid: dem.asc}\n", 8, "scene.terrain.grid",
               "give one of flat_u, grid and dem");
  expect_error(m + "scene:\n  terrain: {grid: dem.asc, dem: dem.tif}\n", 8, "scene.terrain.dem",
               "give one of flat_u, grid and dem");
  expect_error(m + "scene:\n  terrain: {reflectivity: 0.3}\n", 8, "scene.terrain",
               "needs flat_u, grid or dem (or write terrain: none)");
  expect_error(m + "scene:\n  terrain: hills\n", 8, "scene.terrain",
               "expected none, {flat_u: U}, {grid: FILE} or {dem: FILE}, got 'hills'");
}

TEST(ScenarioLoaderErrors, UnreadableFile) {
  try {
    (void)load_scenario("/nonexistent/owsim/s.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "/nonexistent/owsim/s.yaml: cannot read the YAML file: no such file");
  }
}

}  // namespace
}  // namespace owsim
