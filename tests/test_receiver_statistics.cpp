// The receiver's statistics through whole flights (SENSOR-SPEC §11, issue 44 "What must hold"),
// each against an independent scipy computation:
//  - looking at an empty sky, the pulses with a false return equal 1 − exp(−Λ(R)) over the ranges a
//    counter can report, and the first false returns' ranges follow Λ (Kolmogorov–Smirnov), at
//    night and in daylight (the sky's background);
//  - looking down at flat ground whose echo is near the threshold, the ground's detections equal
//    Σ Φ((e − T)/σ_n(R)) over its pulses, at night and in sunlight (the ground's background), with
//    e and R taken from the same flight through the deterministic receiver at threshold 0.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "false_trigger_oracle.hpp"
#include "owsim/simulation.hpp"
#include "python_oracle.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

using test::python_list;
using test::python_number;
using test::run_python;

// A flight at 150 m; `sensor` and `scene` are YAML blocks, `sun` a line (or empty).
std::string scenario(const std::string& sensor, const std::string& scene, const std::string& sun) {
  return "name: statistics\nseed: 9\norigin: {lat: 48.6881, lon: 10.8447, h: 450}\n" + sun +
         "\nsensor:\n" + sensor +
         "atmosphere: {transmission: 0.95}\n"
         "trajectory:\n  waypoints:\n    speed_mps: 40\n"
         "    points: [{e: 0, n: 0, u: 150}, {e: 400, n: 0, u: 150}]\n"
         "scene:\n" +
         scene;
}

struct Flight {
  std::int64_t active_pulses = 0;
  std::vector<const ReturnRecord*> first;  // return 1 of each pulse that has one
  std::vector<ReturnRecord> returns;
};

Flight fly(const std::string& yaml, int frames) {
  SimulationOptions options;
  options.frames = frames;
  const Simulation sim = Simulation::from_yaml(yaml, "statistics.yaml", options);
  Flight flight;
  for (std::int64_t k = 0; k < sim.frame_count(); ++k) {
    const Frame frame = sim.simulate_frame(k);
    for (const Pulse& pulse : frame.pulses()) flight.active_pulses += pulse.reference ? 0 : 1;
    flight.returns.insert(flight.returns.end(), frame.returns().begin(), frame.returns().end());
  }
  for (const ReturnRecord& r : flight.returns) {
    if (r.return_number == 1) flight.first.push_back(&r);
  }
  return flight;
}

// Empty sky: every return is a false one; checked against Λ by quadrature.
void expect_sky_false_returns(const std::string& sun_line, double background) {
  constexpr double kThreshold = 0.004, kNoise = 0.0011;
  const std::string sensor = "  threshold: " + python_number(kThreshold) +
                             "\n  range_noise_sigma_m: 0\n  mount: {pitch_deg: 20}\n"
                             "  receiver: {noise: on, noise_at_1km: " +
                             python_number(kNoise) + ", sun_noise: 3.0, sky_noise: 0.8}\n";
  const Flight flight = fly(scenario(sensor, "  terrain: none\n", sun_line), 3);
  std::vector<double> ranges;
  for (const ReturnRecord* r : flight.first) {
    ASSERT_EQ(r->surface, static_cast<std::uint8_t>(SurfaceClass::noise));
    ASSERT_EQ(r->object, kNoObject);
    ASSERT_EQ(r->energy_rel, kThreshold);
    ranges.push_back(r->range_m);
  }
  // A range reports while round(range / Δ) is below the timeout count.
  const RangeCounterParams counter;
  const double reportable = (counter.timeout_counts - 0.5) * range_per_count_m(counter);
  const std::string out = run_python(
      test::false_trigger_oracle_python(kThreshold, kNoise, background, timeout_range_m(counter)) +
      "R = " + python_number(reportable) + "\nn = " + std::to_string(flight.active_pulses) +
      "\nranges = np.array(" + python_list(ranges) +
      ")\n"
      "p = 1 - np.exp(-Lam(R))\n"
      "z = (len(ranges) - n * p) / np.sqrt(n * p * (1 - p))\n"
      "ks = stats.kstest(ranges, first_cdf(R))\n"
      "print(z, ks.pvalue, n * p)\n");
  const std::vector<double> v = test::numbers_printed(out);
  ASSERT_EQ(v.size(), 3u) << out;
  EXPECT_GT(ranges.size(), 2000u);
  EXPECT_LT(std::abs(v[0]), 5.0) << ranges.size() << " pulses with a false return, expected "
                                 << v[2] << " of " << flight.active_pulses;
  EXPECT_GT(v[1], 1e-4) << "KS p-value of the false returns' ranges";
}

TEST(ReceiverStatistics, FalseReturnsInAnEmptySkyAtNightArePoisson) {
  expect_sky_false_returns("", 0.0);
}

TEST(ReceiverStatistics, FalseReturnsInAnEmptySkyByDayCarryTheSkysBackground) {
  // b = k_sky · sin ε = 0.8 · sin 30°
  expect_sky_false_returns("sun: {elevation_deg: 30, azimuth_deg: 100}", 0.4);
}

// Flat ground of reflectivity 0.1 seen straight down from 150 m: echoes 0.068–0.095, near the
// threshold 0.08 with σ_n(160 m) ≈ T/6, so no false trigger precedes the ground.
void expect_ground_detections_are_sum_of_phi(const std::string& sun_line, double background) {
  constexpr double kThreshold = 0.08, kNoise = 0.52;
  const std::string scene = "  terrain: {flat_u: 0, reflectivity: 0.1}\n";
  const std::string mount = "  mount: {pitch_deg: -90}\n  range_noise_sigma_m: 0\n";
  const Flight plain =
      fly(scenario(mount + "  threshold: 0\n  receiver: {noise: off}\n", scene, sun_line), 2);
  const Flight noisy =
      fly(scenario(mount + "  threshold: " + python_number(kThreshold) +
                       "\n  receiver: {noise: on, noise_at_1km: " + python_number(kNoise) +
                       ", sun_noise: 5.0}\n",
                   scene, sun_line),
          2);
  std::vector<double> energies, ranges;
  for (const ReturnRecord* r : plain.first) {
    ASSERT_EQ(r->surface, static_cast<std::uint8_t>(SurfaceClass::ground));
    energies.push_back(r->energy_rel);
    ranges.push_back(r->range_m);
  }
  ASSERT_EQ(static_cast<std::int64_t>(energies.size()), plain.active_pulses);
  std::int64_t detected = 0;
  for (const ReturnRecord* r : noisy.first) {
    detected += r->surface == static_cast<std::uint8_t>(SurfaceClass::ground) ? 1 : 0;
  }
  const std::string out = run_python(
      "import numpy as np\nfrom scipy.stats import norm\n"
      "e = np.array(" +
      python_list(energies) + ")\nR = np.array(" + python_list(ranges) +
      ")\n"
      "s = " +
      python_number(kNoise) + " * (R / 1000.0) ** 2 * np.sqrt(1 + " + python_number(background) +
      ")\npd = norm.cdf((e - " + python_number(kThreshold) +
      ") / s)\nprint(repr(pd.sum()), repr((pd * (1 - pd)).sum()))\n");
  const std::vector<double> v = test::numbers_printed(out);
  ASSERT_EQ(v.size(), 2u) << out;
  EXPECT_GT(v[1], 500.0) << "too few pulses near the threshold to test";
  EXPECT_LT(std::abs(static_cast<double>(detected) - v[0]), 5.0 * std::sqrt(v[1]))
      << "detected " << detected << ", Σ Φ = " << v[0] << " ± " << std::sqrt(v[1]);
}

TEST(ReceiverStatistics, GroundDetectionsNearTheThresholdAtNightAreTheSumOfPhi) {
  expect_ground_detections_are_sum_of_phi("", 0.0);
}

TEST(ReceiverStatistics, GroundDetectionsNearTheThresholdInSunlightAreTheSumOfPhi) {
  // b = k_sun · A · cos θ_s = 5 · 0.1 · sin 60° for flat ground
  expect_ground_detections_are_sum_of_phi("sun: {elevation_deg: 60, azimuth_deg: 200}",
                                          5.0 * 0.1 * std::sin(60.0 * M_PI / 180.0));
}

}  // namespace
}  // namespace owsim
