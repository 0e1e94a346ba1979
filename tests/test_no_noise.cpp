// Protects what `--no-noise` means (INTERFACE.md "Receiver noise and sunlight": it turns off range
// noise and receiver noise together) everywhere it applies: a Simulation's options (`owsim run`,
// the Python module, the C API), the scenario overrides of `owsim merge`, and the run folder's
// scenario.yaml, which must fly the same receiver again when it is run without the option.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "io/recording/recording_decoder_scene.hpp"
#include "io/scenario/scenario_as_flown.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "minimal_scenario.hpp"
#include "owsim/simulation.hpp"

namespace owsim {
namespace {

// The minimal scenario with its receiver's noise on, a non-default σ_1km and the sun up.
const std::string kNoisy = std::string(test::kMinimalScenario) + R"(sensor:
  range_noise_sigma_m: 0.3
  receiver: {noise: on, noise_at_1km: 0.001}
sun: {time_utc: "2026-06-21T10:30:00Z"}
)";

void expect_noise_off(const Scenario& scenario) {
  EXPECT_EQ(scenario.receiver.range_noise_sigma_m, 0.0);
  EXPECT_FALSE(scenario.receiver.noise.on);
  // Only the switches change: the statistics and the sun stay as written.
  EXPECT_EQ(scenario.receiver.noise.noise_at_1km, 0.001);
  EXPECT_TRUE(scenario.receiver.sun.given);
}

TEST(NoNoise, SimulationOptionsTurnRangeAndReceiverNoiseOff) {
  const Simulation noisy = Simulation::from_yaml(kNoisy, "s.yaml");
  EXPECT_EQ(noisy.scenario().receiver.range_noise_sigma_m, 0.3);
  EXPECT_TRUE(noisy.scenario().receiver.noise.on);
  SimulationOptions options;
  options.no_noise = true;
  expect_noise_off(Simulation::from_yaml(kNoisy, "s.yaml", options).scenario());
}

TEST(NoNoise, MergeOverridesTurnRangeAndReceiverNoiseOff) {
  const test::TempDir folder("owsim_no_noise_merge");
  const std::filesystem::path path = folder / "s.yaml";
  std::ofstream(path) << kNoisy;
  EXPECT_TRUE(load_recording_scenario(path, {}).receiver.noise.on);
  RecordingScenarioOverrides overrides;
  overrides.no_noise = true;
  expect_noise_off(load_recording_scenario(path, overrides));
}

TEST(NoNoise, TheScenarioAsFlownKeepsBothOffWhenRunAgain) {
  const std::filesystem::path path = "/scenarios/s.yaml";
  const Scenario source = load_scenario_text(kNoisy, path);
  FlownOverrides overrides;
  overrides.no_noise = true;
  const FlownScenario flown = scenario_as_flown(kNoisy, path, overrides, source.input_files);
  const Scenario again = load_scenario_text(flown.yaml, path);
  expect_noise_off(again);
  EXPECT_EQ(again.receiver.sun.elevation_deg, source.receiver.sun.elevation_deg);
  EXPECT_EQ(again.receiver.sun.azimuth_deg, source.receiver.sun.azimuth_deg);

  // Without sensor keys at all, the flown file adds them.
  const std::string plain = test::kMinimalScenario;
  const FlownScenario plain_flown = scenario_as_flown(plain, path, overrides, {});
  const Scenario plain_again = load_scenario_text(plain_flown.yaml, path);
  EXPECT_EQ(plain_again.receiver.range_noise_sigma_m, 0.0);
  EXPECT_FALSE(plain_again.receiver.noise.on);

  // Without the option, the receiver is flown as written.
  const FlownScenario as_written = scenario_as_flown(kNoisy, path, {}, source.input_files);
  EXPECT_TRUE(load_scenario_text(as_written.yaml, path).receiver.noise.on);
}

}  // namespace
}  // namespace owsim
