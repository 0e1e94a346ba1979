// Protects one frame of the simulator (engine/frame_simulator.hpp): the reference fiber carries
// the reference counter and no ray, every ray is a unit vector from the sensor, ground returns
// lie on the ground to the millimetre, and a frame's bytes do not depend on the thread count, the
// Embree query form, the buffers reused or the order frames are simulated in (DESIGN.md
// "Determinism"); each pulse's object_returns bits mark exactly its returns on named objects;
// records kept per block (FrameRecordScope::block) are the frame's, block by block.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/frame_simulator.hpp"
#include "scene_fixtures.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

const Eigen::AlignedBox2d kMeshRegion(Eigen::Vector2d(-2000.0, -2000.0),
                                      Eigen::Vector2d(2000.0, 2000.0));

Scene flat_ground(double height_m) {
  Scene scene;
  scene.terrain.kind = TerrainKind::flat;
  scene.terrain.flat_u_m = height_m;
  return scene;
}

// 100 m above flat ground, nose 30° down, so the whole ±21° fan meets the ground.
Pose looking_down(double ground_m) {
  Pose pose;
  pose.position_enu_m = Eigen::Vector3d(123.0, -456.0, ground_m + 100.0);
  pose.attitude.heading_deg = 37.0;
  pose.attitude.pitch_deg = -30.0;
  pose.attitude.roll_deg = 5.0;
  return pose;
}

TEST(FrameSimulator, ReferenceFiberCarriesTheReferenceCounterAndNoRay) {
  const Scene scene = flat_ground(0.0);
  FrameSimulatorParams params;
  params.receiver.range_noise_sigma_m = 0.0;
  const EmbreeDevice device;
  const EmbreeScene embree(device, scene, params.receiver, kMeshRegion,
                           timeout_range_m(params.receiver.counter));
  const FrameSimulator simulator(params, embree, TraceApi::stream);
  FrameResult out;
  simulator.simulate(4, FixedPose(looking_down(0.0)), out);
  ASSERT_EQ(out.returns.size(), 20352u);
  std::vector<PulseCandidates> candidates(out.rays.size());
  simulator.tracer().trace(out.rays, out.active, candidates);
  EXPECT_EQ(out.frame, 4);
  int references = 0;
  for (std::size_t k = 0; k < out.pulses.size(); ++k) {
    if (!out.pulses[k].reference) {
      EXPECT_EQ(out.active[k], 1) << k;
      continue;
    }
    ++references;
    EXPECT_EQ(out.active[k], 0) << k;
    EXPECT_EQ(out.pulses[k].fiber, 128);
    EXPECT_TRUE(candidates[k].wires().empty());
    EXPECT_FALSE(candidates[k].has_solid());
    EXPECT_EQ(out.returns[k].count, 0);
    EXPECT_EQ(out.returns[k].counter1, 10);  // SENSOR-SPEC §8 reference range, noise off
    EXPECT_EQ(out.returns[k].counter2, 2066);
  }
  EXPECT_EQ(references, 159);  // one a line
}

TEST(FrameSimulator, RaysAreUnitVectorsFromTheSensor) {
  const Scene scene = flat_ground(0.0);
  FrameSimulatorParams params;
  params.mount.lever_arm_m = Eigen::Vector3d(2.0, 0.5, 1.0);
  const EmbreeDevice device;
  const EmbreeScene embree(device, scene, params.receiver, kMeshRegion,
                           timeout_range_m(params.receiver.counter));
  const FrameSimulator simulator(params, embree, TraceApi::per_ray);
  FrameResult out;
  const test::LevelFlight flight(Eigen::Vector3d(0.0, 0.0, 150.0), 75.0, 60.0);
  simulator.build_rays(1, flight, out);
  const SensorModel model = params.scan.model;
  for (std::size_t k = 0; k < out.rays.size(); ++k) {
    if (out.active[k] == 0) continue;
    EXPECT_NEAR(out.rays[k].dir_enu.norm(), 1.0, 1e-12) << k;
    // The origin is the sensor at the pulse's own firing time.
    const SensorPlacement placement =
        sensor_placement(flight.pose_at(out.pulses[k].time_s), params.mount, model);
    EXPECT_NEAR((out.rays[k].origin_enu_m - placement.origin_enu_m).norm(), 0.0, 1e-9) << k;
  }
  // The sensor moves 60 m/s · 0.333 s ≈ 20 m over the frame.
  const double moved =
      (out.rays[out.rays.size() - 2].origin_enu_m - out.rays[0].origin_enu_m).norm();
  EXPECT_NEAR(moved, 60.0 * 20350.0 / params.scan.prf_hz, 1e-6);
}

TEST(FrameSimulator, GroundReturnsLieOnTheGround) {
  const double ground = 37.25;
  const Scene scene = flat_ground(ground);
  FrameSimulatorParams params;
  params.receiver.range_noise_sigma_m = 0.0;
  params.receiver.noise.on = false;  // the ground's geometry alone: no false return behind it
  const EmbreeDevice device;
  const EmbreeScene embree(device, scene, params.receiver, kMeshRegion,
                           timeout_range_m(params.receiver.counter));
  const FrameSimulator simulator(params, embree, TraceApi::packet8);
  FrameResult out;
  simulator.simulate(0, FixedPose(looking_down(ground)), out);
  const double delta = range_per_count_m(params.receiver.counter);
  int returns = 0;
  for (std::size_t k = 0; k < out.returns.size(); ++k) {
    const PulseReturns& pulse = out.returns[k];
    if (out.active[k] == 0) continue;
    ASSERT_LE(pulse.count, 1) << k;  // one surface, one return
    if (pulse.count == 0) continue;
    ++returns;
    const Return& r = pulse.returns[0];
    EXPECT_EQ(r.surface, static_cast<std::uint8_t>(SurfaceClass::ground));
    EXPECT_EQ(r.range_m, r.true_range_m);  // noise off
    const Eigen::Vector3d point = out.rays[k].origin_enu_m + r.range_m * out.rays[k].dir_enu;
    EXPECT_NEAR(point.z(), ground, 1e-3) << k;
    EXPECT_EQ(pulse.counter1, static_cast<std::uint16_t>(std::lround(r.range_m / delta))) << k;
    EXPECT_EQ(pulse.counter2, 2066);
  }
  // Nearly every pulse sees the ground (the shallowest rays, 9° down, are the faintest).
  EXPECT_GT(returns, 19000);
}

// Every byte that matters of a frame's returns, for bit-for-bit comparison.
std::vector<std::uint64_t> fingerprint(const FrameResult& out) {
  std::vector<std::uint64_t> words;
  for (const PulseReturns& pulse : out.returns) {
    words.push_back(static_cast<std::uint64_t>(pulse.count));
    words.push_back(pulse.counter1);
    words.push_back(pulse.counter2);
    for (int r = 0; r < pulse.count; ++r) {
      const Return& x = pulse.returns[r];
      words.push_back(std::bit_cast<std::uint64_t>(x.range_m));
      words.push_back(std::bit_cast<std::uint64_t>(x.true_range_m));
      words.push_back(std::bit_cast<std::uint64_t>(x.energy_rel));
      words.push_back(std::bit_cast<std::uint64_t>(x.incidence_deg));
      words.push_back(x.counter);
      words.push_back(x.object_index);
      words.push_back(x.surface);
    }
  }
  return words;
}

// Level flight at 30 m/s from the scene's sensor towards its first span's middle.
test::LevelFlight toward_first_span(const test::RandomScene& made) {
  const Conductor& wire = made.scene.conductors.front();
  const Eigen::Vector3d middle = wire.points_enu_m[wire.points_enu_m.size() / 2];
  const Eigen::Vector3d sight = middle - made.sensor_enu_m;
  const double heading = std::atan2(sight.x(), sight.y()) * 180.0 / std::numbers::pi;
  return test::LevelFlight(made.sensor_enu_m, heading, 30.0);
}

TEST(FrameSimulator, FramesAreBitIdenticalAcrossThreadsApisAndOrder) {
  const test::RandomScene made =
      test::random_scene(77, {.spans = 4, .trees = 10, .sloped_grid = true, .max_range_m = 500.0});
  FrameSimulatorParams params;  // default noise: the keyed draws must not depend on threads
  params.seed = 1234;
  const EmbreeDevice device;
  const EmbreeScene embree(device, made.scene, params.receiver, made.region,
                           timeout_range_m(params.receiver.counter));
  const test::LevelFlight flight = toward_first_span(made);

  std::vector<std::uint64_t> expected;
  int wire_returns = 0;
  for (TraceApi api : kTraceApis) {
    const FrameSimulator simulator(params, embree, api);
    for (int threads : {1, 2}) {
      tbb::task_arena arena(threads);
      FrameResult out;
      arena.execute([&] {
        simulator.simulate(3, flight, out);  // frame 3 first, then frame 2 into the same buffers
        simulator.simulate(2, flight, out);
      });
      const std::vector<std::uint64_t> words = fingerprint(out);
      if (expected.empty()) {
        expected = words;
        for (const PulseReturns& pulse : out.returns) {
          for (int r = 0; r < pulse.count; ++r) {
            wire_returns +=
                pulse.returns[r].surface == static_cast<std::uint8_t>(SurfaceClass::wire) ? 1 : 0;
          }
        }
        continue;
      }
      EXPECT_TRUE(words == expected) << to_string(api) << " with " << threads << " threads";
    }
  }
  // Frame 2 alone in a fresh buffer gives the same bytes too.
  FrameResult alone;
  FrameSimulator(params, embree, TraceApi::stream).simulate(2, flight, alone);
  EXPECT_TRUE(fingerprint(alone) == expected);
  EXPECT_GT(expected.size(), 100000u);
  EXPECT_GT(wire_returns, 0);  // the comparison covers wire returns, not only ground
}

TEST(FrameSimulator, ObjectReturnBitsMarkTheReturnsOnNamedObjects) {
  const test::RandomScene made =
      test::random_scene(78, {.spans = 4, .trees = 30, .sloped_grid = true, .max_range_m = 500.0});
  FrameSimulatorParams params;
  params.seed = 99;
  const EmbreeDevice device;
  const EmbreeScene embree(device, made.scene, params.receiver, made.region,
                           timeout_range_m(params.receiver.counter));
  const test::LevelFlight flight = toward_first_span(made);
  const std::size_t named = named_object_count(made.scene);
  int on_objects = 0, on_ground = 0;
  FrameResult out;
  for (const std::int64_t frame : {2, 3}) {  // the second into the first's buffers
    FrameSimulator(params, embree, TraceApi::stream).simulate(frame, flight, out);
    ASSERT_EQ(out.object_returns.size(), out.returns.size());
    for (std::size_t k = 0; k < out.returns.size(); ++k) {
      const PulseReturns& pulse = out.returns[k];
      unsigned expected = 0;
      for (int r = 0; r < pulse.count; ++r) {
        const bool named_object = pulse.returns[r].object_index < named;
        expected |= named_object ? 1u << r : 0u;
        (named_object ? on_objects : on_ground) += 1;
      }
      ASSERT_EQ(out.object_returns[k], expected) << "frame " << frame << " pulse " << k;
    }
  }
  EXPECT_GT(on_objects, 50);  // wires and trees were hit, and the ground: both bits are tested
  EXPECT_GT(on_ground, 1000);
}

// FrameRecordScope::block: each block's records reach the callback in the worker's scratch and
// the FrameResult keeps none; put back together they are the frame's records, byte for byte.
TEST(FrameSimulator, RecordsKeptPerBlockAreTheFramesBlockByBlock) {
  const test::RandomScene made =
      test::random_scene(79, {.spans = 4, .trees = 20, .sloped_grid = true, .max_range_m = 500.0});
  FrameSimulatorParams params;
  params.seed = 4321;
  const EmbreeDevice device;
  const EmbreeScene embree(device, made.scene, params.receiver, made.region,
                           timeout_range_m(params.receiver.counter));
  const test::LevelFlight flight = toward_first_span(made);
  const FrameSimulator simulator(params, embree, TraceApi::packet8);
  FrameResult whole;
  simulator.simulate(5, flight, whole);

  FrameResult assembled;  // the blocks' records copied to their places
  assembled.pulses.resize(whole.pulses.size());
  assembled.rays.resize(whole.rays.size());
  assembled.returns.resize(whole.returns.size());
  assembled.object_returns.resize(whole.object_returns.size());
  std::vector<std::atomic<int>> seen(whole.pulses.size());
  FrameResult blocks;
  tbb::task_arena arena(2);
  arena.execute([&] {
    simulator.simulate(
        5, flight, blocks,
        [&](const FrameResult& frame, const FrameView& block, int begin) {
          EXPECT_EQ(frame.frame, 5);
          EXPECT_TRUE(frame.pulses.empty() && frame.returns.empty());
          const auto at = static_cast<std::ptrdiff_t>(begin);
          std::copy(block.pulses.begin(), block.pulses.end(), assembled.pulses.begin() + at);
          std::copy(block.rays.begin(), block.rays.end(), assembled.rays.begin() + at);
          std::copy(block.returns.begin(), block.returns.end(), assembled.returns.begin() + at);
          std::copy(block.object_returns.begin(), block.object_returns.end(),
                    assembled.object_returns.begin() + at);
          for (std::size_t k = 0; k < block.pulses.size(); ++k) {
            EXPECT_EQ(block.pulses[k].index, begin + static_cast<int>(k));
            seen[static_cast<std::size_t>(begin) + k] += 1;
          }
        },
        FrameRecordScope::block);
  });
  EXPECT_TRUE(blocks.pulses.empty() && blocks.rays.empty() && blocks.active.empty() &&
              blocks.returns.empty() && blocks.object_returns.empty());
  EXPECT_EQ(blocks.sweep.direction, whole.sweep.direction);
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](const auto& n) { return n == 1; }));
  EXPECT_TRUE(fingerprint(assembled) == fingerprint(whole));
  EXPECT_TRUE(assembled.object_returns == whole.object_returns);
  for (std::size_t k = 0; k < whole.pulses.size(); ++k) {
    ASSERT_EQ(assembled.pulses[k].time_s, whole.pulses[k].time_s) << k;
    ASSERT_EQ(assembled.pulses[k].encoder, whole.pulses[k].encoder) << k;
    ASSERT_EQ(assembled.rays[k].dir_enu, whole.rays[k].dir_enu) << k;
    ASSERT_EQ(assembled.rays[k].origin_enu_m, whole.rays[k].origin_enu_m) << k;
  }
}

}  // namespace
}  // namespace owsim
