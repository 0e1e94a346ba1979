// Protects the headline behaviour of the sensor model (SENSOR-SPEC §7): with the default 1 mrad
// divergence, 0.005 threshold and 0.95 transmission, a 20 mm conductor crossing the flight path
// (reflectivity 0.4) is detected at every range up to the counter timeout, and a 5 mm one only
// up to max_detection_range_m (≈ 484 m) — shown by whole simulated MilOWS frames, hovering and in
// level flight, with the wire perpendicular to the heading at the height of the α = 0 fibers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/frame_simulator.hpp"
#include "scene_fixtures.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

// SENSOR-SPEC §7's deterministic receiver at the spec's example threshold 0.005 (owsim 0.1.0's
// default): the edges below are those of the energy alone, without §11's noise.
ReceiverParams spec_receiver() {
  ReceiverParams p;
  p.threshold = 0.005;
  p.noise.on = false;
  return p;
}

constexpr double kSensorHeight_m = 150.0;
constexpr double kSpeed_mps = 40.0;

// A straight horizontal conductor along east–west, `range_m` north of the sensor, at the
// sensor's height (the α = 0 fibers 64 and 127 cross it on every line), over flat ground.
Scene wire_across(double range_m, double diameter_m) {
  Scene scene;
  scene.terrain.kind = TerrainKind::flat;
  scene.terrain.flat_u_m = 0.0;
  Conductor wire;
  wire.id = "crossing/1";
  wire.radius_m = 0.5 * diameter_m;
  wire.reflectivity = 0.4;
  for (double e = -1500.0; e <= 1500.0; e += 100.0)
    wire.points_enu_m.emplace_back(e, range_m, kSensorHeight_m);
  scene.conductors.push_back(wire);
  return scene;
}

struct WireSighting {
  int returns = 0;         // wire returns in the frame
  double nearest_m = 0.0;  // their true ranges
  double farthest_m = 0.0;
};

// Simulates frames 0 and 1 (both sweep directions) of a sensor flying north at `speed_mps`,
// placed so the wire is `range_m` ahead at the middle of frame 0.
WireSighting sight_wire(double range_m, double diameter_m, double speed_mps) {
  const Scene scene = wire_across(range_m, diameter_m);
  FrameSimulatorParams params;  // MilOWS, SENSOR-SPEC §7's deterministic receiver at 0.005
  params.receiver = spec_receiver();
  const EmbreeDevice device;
  const EmbreeScene embree(
      device, scene, params.receiver,
      Eigen::AlignedBox2d(Eigen::Vector2d(-2000.0, -2000.0), Eigen::Vector2d(2000.0, 2000.0)),
      timeout_range_m(params.receiver.counter));
  const FrameSimulator simulator(params, embree, TraceApi::stream);
  const double half_frame_s = 0.5 * params.scan.frame_duration_s();
  const test::LevelFlight flight(Eigen::Vector3d(0.0, -speed_mps * half_frame_s, kSensorHeight_m),
                                 0.0, speed_mps);
  WireSighting sighting{0, INFINITY, 0.0};
  FrameResult out;
  for (std::int64_t frame : {0, 1}) {
    simulator.simulate(frame, flight, out);
    for (const PulseReturns& pulse : out.returns) {
      for (int r = 0; r < pulse.count; ++r) {
        const Return& x = pulse.returns[r];
        if (x.surface != static_cast<std::uint8_t>(SurfaceClass::wire)) continue;
        EXPECT_EQ(x.object_index, 0u);
        EXPECT_GE(x.energy_rel, params.receiver.threshold);
        ++sighting.returns;
        sighting.nearest_m = std::min(sighting.nearest_m, x.true_range_m);
        sighting.farthest_m = std::max(sighting.farthest_m, x.true_range_m);
      }
    }
  }
  return sighting;
}

const std::vector<double> kRanges_m = {100, 300, 450, 500, 700, 1000, 1200};

TEST(WireDetection, TwentyMillimetreWireIsSeenUpToTheTimeout) {
  const ReceiverParams defaults = spec_receiver();
  EXPECT_GE(max_detection_range_m(0.020, 0.4, defaults), timeout_range_m(defaults.counter));
  for (double speed : {0.0, kSpeed_mps}) {
    for (double range : kRanges_m) {
      const WireSighting sighting = sight_wire(range, 0.020, speed);
      std::printf("20 mm wire at %6.0f m, %2.0f m/s: %4d returns, true range %.1f–%.1f m\n", range,
                  speed, sighting.returns, sighting.nearest_m, sighting.farthest_m);
      EXPECT_GT(sighting.returns, 0) << range << " m";
      if (sighting.returns == 0) continue;
      // β up to ±18.4° makes the slant range up to 1/cos β longer; over the two frames the
      // sensor flies from half a frame before to 1.5 frames after the nominal position.
      const double flown = 1.5 * speed * FrameSimulatorParams{}.scan.frame_duration_s() + 0.1;
      EXPECT_GT(sighting.nearest_m, range - flown);
      EXPECT_LT(sighting.farthest_m, range / std::cos(test::radians(18.5)) + flown);
      // Hovering, the nearest return is the pulse with β closest to 0: the wire's own distance.
      if (speed == 0.0) EXPECT_NEAR(sighting.nearest_m, range, 1e-4 * range);
    }
  }
}

TEST(WireDetection, FiveMillimetreWireOnlyWithinItsMaximumRange) {
  const ReceiverParams defaults = spec_receiver();
  const double limit = max_detection_range_m(0.005, 0.4, defaults);
  EXPECT_NEAR(limit, 484.0, 2.0);
  for (double speed : {0.0, kSpeed_mps}) {
    for (double range : kRanges_m) {
      const WireSighting sighting = sight_wire(range, 0.005, speed);
      std::printf("5 mm wire at %6.0f m, %2.0f m/s: %4d returns\n", range, speed, sighting.returns);
      // A margin of 3 % on either side of the head-on limit: off-centre beams (d ≠ 0), β ≠ 0
      // incidence and the flight's ±7 m blur the edge.
      if (range < 0.97 * limit) {
        EXPECT_GT(sighting.returns, 0) << range << " m";
      } else if (range > 1.03 * limit) {
        EXPECT_EQ(sighting.returns, 0) << range << " m";
      }
    }
  }
}

// The detection edge found by simulation sits at the computed maximum range: the farthest range
// (1 m steps) at which a hovering sensor still records the 5 mm wire is within 1 % below it.
TEST(WireDetection, SimulatedEdgeMatchesMaxDetectionRange) {
  const ReceiverParams defaults = spec_receiver();
  const double limit = max_detection_range_m(0.005, 0.4, defaults);
  double farthest_seen = 0.0;
  double nearest_unseen = INFINITY;
  for (double range = std::floor(0.98 * limit); range <= std::ceil(1.01 * limit); range += 1.0) {
    const WireSighting sighting = sight_wire(range, 0.005, 0.0);
    if (sighting.returns > 0) farthest_seen = std::max(farthest_seen, range);
    if (sighting.returns == 0) nearest_unseen = std::min(nearest_unseen, range);
  }
  std::printf("5 mm wire: max_detection_range_m %.2f m, last seen at %.0f m, first unseen %.0f m\n",
              limit, farthest_seen, nearest_unseen);
  EXPECT_LE(farthest_seen, limit);
  EXPECT_GE(farthest_seen, 0.99 * limit);
  EXPECT_GT(nearest_unseen, farthest_seen);  // one clean edge
}

}  // namespace
}  // namespace owsim
