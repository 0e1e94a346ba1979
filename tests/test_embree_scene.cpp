// Protects the scene as Embree sees it (engine/embree_scene.hpp, engine/embree_device.hpp): the
// geometry ids and capture radius, the input checks, and the cases where float geometry and the
// double-precision rules could part — rays inside a wire's capture tube along many segments, the
// free ends of a conductor, the silhouette edge and top of a cylinder, and terrain edges and
// corners at grazing incidence — each checked against the brute-force tracer and closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/brute_force_tracer.hpp"
#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "engine/frame_tracer.hpp"
#include "geometry/cylinder.hpp"
#include "geometry/error.hpp"
#include "scene_fixtures.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

const Eigen::AlignedBox2d kRegion(Eigen::Vector2d(-2000.0, -2000.0),
                                  Eigen::Vector2d(2000.0, 2000.0));

double timeout_m() { return timeout_range_m(RangeCounterParams{}); }

// Traces rays with every API and with brute force; returns the per-API results after checking
// they agree among themselves (solid and wires by object) and with brute force.
std::vector<PulseCandidates> trace_all(const EmbreeScene& scene, const Scene& objects,
                                       const std::vector<PulseRay>& rays) {
  const std::vector<std::uint8_t> active(rays.size(), 1);
  std::vector<PulseCandidates> reference(rays.size());
  BruteForceTracer(objects, scene.terrain_mesh(), scene.receiver()).trace(rays, active, reference);
  for (TraceApi api : kTraceApis) {
    std::vector<PulseCandidates> traced(rays.size());
    FrameTracer(scene, api).trace(rays, active, traced);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      SCOPED_TRACE(std::string(to_string(api)) + " ray " + std::to_string(i));
      EXPECT_EQ(traced[i].has_solid(), reference[i].has_solid());
      if (traced[i].has_solid() && reference[i].has_solid()) {
        EXPECT_EQ(traced[i].solid().object_index, reference[i].solid().object_index);
        EXPECT_NEAR(traced[i].solid().range_m, reference[i].solid().range_m, 1e-3);
      }
      EXPECT_EQ(traced[i].wires().size(), reference[i].wires().size());
      for (const Candidate& wire : reference[i].wires()) {
        bool found = false;
        for (const Candidate& other : traced[i].wires()) {
          if (other.object_index != wire.object_index) continue;
          found = true;
          EXPECT_EQ(other.range_m, wire.range_m);  // the same segment, the same double maths
          EXPECT_EQ(other.energy_rel, wire.energy_rel);
        }
        EXPECT_TRUE(found) << "wire " << wire.object_index;
      }
    }
  }
  return reference;
}

Conductor straight_wire(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int segments,
                        double radius_m) {
  Conductor conductor;
  conductor.id = "wire/1";
  conductor.radius_m = radius_m;
  for (int i = 0; i <= segments; ++i)
    conductor.points_enu_m.push_back(from + (to - from) * (static_cast<double>(i) / segments));
  return conductor;
}

TEST(EmbreeScene, GeometryIdsFollowTheSceneOrder) {
  const test::RandomScene made = test::random_scene(3, {.spans = 2, .trees = 2});
  const EmbreeDevice device;
  const EmbreeScene scene(device, made.scene, ReceiverParams{}, made.region, timeout_m());
  // Conductors live in the wires scene, all their segments in its one geometry; cylinders in the
  // solids scene, then a terrain that is not flat. The flat one is outside Embree: the region's
  // two triangles, as the terrain makes them.
  EXPECT_NE(scene.wires(), scene.solids());
  EXPECT_EQ(scene.cylinders_geom_id(), 0u);
  ASSERT_EQ(made.scene.terrain.kind, TerrainKind::flat);
  EXPECT_EQ(scene.terrain_geom_id(), RTC_INVALID_GEOMETRY_ID);
  EXPECT_TRUE(scene.has_terrain());
  const std::vector<TriangleFrame> flat = triangle_frames(made.scene.terrain.mesh(made.region));
  ASSERT_EQ(scene.level_ground().size(), 2u);
  for (std::size_t k = 0; k < flat.size(); ++k) {
    EXPECT_EQ(scene.level_ground()[k].v0, flat[k].v0);
    EXPECT_EQ(scene.level_ground()[k].edge1, flat[k].edge1);
    EXPECT_EQ(scene.level_ground()[k].edge2, flat[k].edge2);
  }
  Scene sloped = made.scene;
  test::Rng rng(3);
  sloped.terrain = test::random_terrain(rng, true, 1800.0);
  const EmbreeScene on_a_grid(device, sloped, ReceiverParams{}, made.region, timeout_m());
  EXPECT_EQ(on_a_grid.terrain_geom_id(), 1u);
  EXPECT_FALSE(on_a_grid.has_level_ground());
  ASSERT_NE(rtcGetGeometry(scene.wires(), 0), nullptr);
  ASSERT_GT(made.scene.conductors.size(), 1u);
  // Geometry segment k maps back to conductor c's own segment k − first_segment[c].
  const WireSegments& table = scene.wire_segments();
  ASSERT_EQ(table.first_segment.size(), made.scene.conductors.size());
  std::size_t k = 0;
  for (std::uint32_t c = 0; c < made.scene.conductors.size(); ++c) {
    EXPECT_EQ(table.first_segment[c], k);
    for (std::size_t s = 0; s + 1 < made.scene.conductors[c].points_enu_m.size(); ++s, ++k) {
      ASSERT_LT(k, table.conductor_of.size());
      EXPECT_EQ(table.conductor_of[k], c);
    }
  }
  EXPECT_EQ(k, table.conductor_of.size());
  EXPECT_EQ(&scene.scene(), &made.scene);

  Scene bare;
  bare.terrain.kind = TerrainKind::none;
  bare.conductors.push_back(straight_wire({0, 0, 0}, {10, 0, 0}, 1, 0.01));
  const EmbreeScene wires_only(device, bare, ReceiverParams{}, kRegion, timeout_m());
  EXPECT_EQ(wires_only.cylinders_geom_id(), RTC_INVALID_GEOMETRY_ID);
  EXPECT_EQ(wires_only.terrain_geom_id(), RTC_INVALID_GEOMETRY_ID);
  EXPECT_FALSE(wires_only.has_terrain());
  EXPECT_TRUE(wires_only.terrain_mesh().triangles.empty());
}

TEST(EmbreeScene, CaptureRadiusCoversTheBeamAtTheTimeout) {
  Scene objects;
  objects.conductors.push_back(straight_wire({0, 0, 0}, {10, 0, 0}, 1, 0.0125));
  ReceiverParams receiver;
  receiver.beam.divergence_mrad = 2.0;
  receiver.beam.exit_radius_m = 0.01;
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, receiver, kRegion, 1000.0);
  // r_wire + r_exit + R·tan(1 mrad) = 0.0125 + 0.01 + 1.0000003
  const double exact = 0.0125 + 0.01 + 1000.0 * std::tan(1e-3);
  const double capture = scene.capture_radius_m(objects.conductors[0]);
  EXPECT_GE(capture, exact);
  EXPECT_LT(capture, exact * 1.01);
}

TEST(EmbreeScene, RejectsBadInput) {
  Scene objects;
  objects.conductors.push_back(straight_wire({0, 0, 0}, {10, 0, 0}, 1, 0.01));
  const EmbreeDevice device;
  EXPECT_THROW(EmbreeScene(device, objects, ReceiverParams{}, kRegion, 0.0), Error);
  EXPECT_THROW(EmbreeScene(device, objects, ReceiverParams{}, kRegion, NAN), Error);
  EXPECT_THROW(EmbreeScene(device, objects, ReceiverParams{}, kRegion, INFINITY), Error);
  objects.conductors[0].points_enu_m.resize(1);
  EXPECT_THROW(EmbreeScene(device, objects, ReceiverParams{}, kRegion, 1000.0), Error);
  EXPECT_NO_THROW(EmbreeDevice("threads=1").check("a fresh device"));
}

// 16-ray packets only where Embree runs them on 16 lanes: a device held to AVX2 (or less, on a
// machine without it) traces 8-ray packets, since it would split the 16 into two.
TEST(EmbreeScene, TheWidestNativePacketFollowsTheDevicesLanes) {
  EXPECT_EQ(widest_native_packet(EmbreeDevice("isa=avx2")), TraceApi::packet8);
  EXPECT_EQ(widest_native_packet(EmbreeDevice("isa=sse4.2")), TraceApi::packet8);
  const EmbreeDevice device;
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
                      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
                      __builtin_cpu_supports("avx512dq");
  EXPECT_EQ(widest_native_packet(device), avx512 ? TraceApi::packet16 : TraceApi::packet8);
}

TEST(EmbreeScene, TerrainMeshIsTheRegionsMesh) {
  test::Rng rng(5);
  Scene objects;
  objects.terrain = test::random_terrain(rng, true, 1800.0);
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, ReceiverParams{}, kRegion, timeout_m());
  const TriangleMesh expected = objects.terrain.mesh(kRegion);
  EXPECT_EQ(scene.terrain_mesh().triangles, expected.triangles);
  EXPECT_EQ(scene.terrain_mesh().vertices, expected.vertices);
  EXPECT_GT(expected.triangles.size(), 100u);
}

// A ray inside the capture tube of a straight conductor of many short segments, nearly parallel
// to it, crossing its axis at one segment: every segment the beam sweeps must reach the exact
// test, so the strongest — the one the ray crosses — is the one reported, as brute force finds.
TEST(EmbreeScene, EdgeOnRayInsideTheCaptureTubeFindsTheStrongestSegment) {
  Scene objects;
  objects.terrain.kind = TerrainKind::none;
  // 200 m of wire in 1 m segments, 300 m north of the sensor.
  objects.conductors.push_back(straight_wire({0, 300, 50}, {0, 500, 50}, 200, 0.01));
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, ReceiverParams{}, kRegion, timeout_m());
  std::vector<PulseRay> rays;
  for (int i = 0; i < 40; ++i) {
    // Aim at the axis at y = 320 + 4·i, from the prolongation, tilted 0.05°..2°.
    const double tilt = (0.05 + 0.05 * i) * std::numbers::pi / 180.0;
    const Eigen::Vector3d target(0.0, 320.0 + 4.0 * i + 0.37, 50.0);
    const Eigen::Vector3d dir(std::sin(tilt) * std::cos(i), std::cos(tilt),
                              std::sin(tilt) * std::sin(i));
    rays.push_back(PulseRay{target - 300.0 * dir, dir});
  }
  const auto reference = trace_all(scene, objects, rays);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(reference[i].wires().size(), 1u) << i;
    // The strongest segment lies between the wire's start (~276 m along the ray, where the
    // beam is narrowest) and the crossing point (300 m), never past the crossing.
    EXPECT_GT(reference[i].wires()[0].range_m, 275.0) << i;
    EXPECT_LT(reference[i].wires()[0].range_m, 301.0) << i;
  }
}

// Round caps at both free ends: a ray just beyond an end, inside the capture distance, is a
// candidate; one outside is not.
TEST(EmbreeScene, ConductorEndsAreCapped) {
  Scene objects;
  objects.terrain.kind = TerrainKind::none;
  objects.conductors.push_back(straight_wire({-50, 400, 30}, {50, 400, 30}, 4, 0.01));
  const ReceiverParams receiver;
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, receiver, kRegion, timeout_m());
  const double limit = 0.01 + beam_radius_m(400.0, receiver.beam);  // 0.21 m
  std::vector<PulseRay> rays;
  for (double beyond : {0.5, 0.9, 0.99, 1.01, 1.2}) {
    for (double end : {-50.0, 50.0}) {
      const double e = end + std::copysign(beyond * limit, end);
      rays.push_back(PulseRay{{e, 0.0, 30.0}, Eigen::Vector3d::UnitY()});
    }
  }
  const auto reference = trace_all(scene, objects, rays);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(reference[i].wires().size(), i < 6 ? 1u : 0u) << i;
  }
}

// A sharp bend: rays aimed past the outside of the corner, where the nearest point of both
// segments is the shared vertex, are candidates exactly as far as the beam reaches.
TEST(EmbreeScene, OutsideOfABendIsCoveredUpToTheBeam) {
  Scene objects;
  objects.terrain.kind = TerrainKind::none;
  Conductor corner = straight_wire({-50, 400, 30}, {0, 400, 30}, 5, 0.01);
  corner.points_enu_m.emplace_back(0.0, 450.0, 30.0);  // a right angle at (0, 400, 30)
  objects.conductors.push_back(corner);
  const ReceiverParams receiver;
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, receiver, kRegion, timeout_m());
  std::vector<PulseRay> rays;
  std::vector<bool> expected;
  // Rays straight down onto the plane z = 30, past the outer corner along the bisector.
  for (double factor : {0.3, 0.8, 0.98, 1.02, 1.5}) {
    const double limit = 0.01 + beam_radius_m(100.0, receiver.beam);
    const double offset = factor * limit / std::sqrt(2.0);
    rays.push_back(PulseRay{{offset, 400.0 - offset, 130.0}, -Eigen::Vector3d::UnitZ()});
    expected.push_back(factor < 1.0);
  }
  const auto reference = trace_all(scene, objects, rays);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(reference[i].wires().size(), expected[i] ? 1u : 0u) << i;
  }
}

// Wires crossing rays a fraction of a millimetre in front of the ground, far from the origin
// (float steps of ~0.1 mm), at random slant: each one in front is found, as by the brute-force
// tracer, whatever the float rounding of the depth Embree reports; those behind are not.
TEST(EmbreeScene, WiresJustInFrontOfTheSolidAreFound) {
  test::Rng rng(19);
  Scene objects;  // flat ground at u = 0
  std::vector<PulseRay> rays;
  std::vector<double> gaps;
  for (int k = 0; k < 300; ++k) {
    const double azimuth = test::uniform(rng, 0.0, 2.0 * std::numbers::pi);
    const double depression = test::uniform(rng, 4.0, 30.0) * std::numbers::pi / 180.0;
    const Eigen::Vector3d dir(std::cos(depression) * std::sin(azimuth),
                              std::cos(depression) * std::cos(azimuth), -std::sin(depression));
    const Eigen::Vector3d origin(test::uniform(rng, -1500.0, 1500.0),
                                 test::uniform(rng, -1500.0, 1500.0), 60.0);
    const double ground_range = 60.0 / std::sin(depression);
    // Mostly within a few float steps of the ground, a few clearly behind it.
    const double gap =
        k % 10 == 0 ? -test::uniform(rng, 0.0, 3e-4) : test::uniform(rng, 1e-6, 3e-4);
    const Eigen::Vector3d crossing = origin + (ground_range - gap) * dir;
    const Eigen::Vector3d across(std::cos(azimuth), -std::sin(azimuth), 0.0);
    objects.conductors.push_back(
        straight_wire(crossing - 0.5 * across, crossing + 0.5 * across, 1, 0.01));
    rays.push_back(PulseRay{origin, dir});
    gaps.push_back(gap);
  }
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, ReceiverParams{}, kRegion, timeout_m());
  const auto reference = trace_all(scene, objects, rays);
  for (std::size_t k = 0; k < rays.size(); ++k) {
    ASSERT_TRUE(reference[k].has_solid()) << k;
    bool own = false;
    for (const Candidate& wire : reference[k].wires()) own = own || wire.object_index == k;
    EXPECT_EQ(own, gaps[k] > 0.0) << k << " gap " << gaps[k];
  }
}

// A conductor running almost along the ray (0.5°, faint: incidence 89.5°) turns across it just
// behind a pole, where it would be strong (incidence 0°). The ray stops at the pole, so the
// conductor's candidate is its strongest segment in front of the pole — not dropped because a
// hidden segment is stronger, and not dependent on the order Embree visits the segments in.
TEST(EmbreeScene, ConductorCandidateIsItsStrongestVisibleSegment) {
  Scene objects;
  objects.terrain.kind = TerrainKind::none;
  Conductor wire = straight_wire({100.0 * std::tan(0.5 * std::numbers::pi / 180.0), 100.0, 10.0},
                                 {0.0, 200.0, 10.0}, 100, 0.01);
  wire.points_enu_m.emplace_back(100.0, 200.0, 10.0);  // across the ray at 200 m
  objects.conductors.push_back(wire);
  Cylinder pole;
  pole.id = "pole";
  pole.base_enu_m = Eigen::Vector3d(0.2, 195.3, 0.0);
  pole.radius_m = 0.3;
  pole.height_m = 30.0;
  objects.cylinders.push_back(pole);
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, ReceiverParams{}, kRegion, timeout_m());
  const std::vector<PulseRay> rays = {{{0.0, 0.0, 10.0}, Eigen::Vector3d::UnitY()}};
  const auto reference = trace_all(scene, objects, rays);
  ASSERT_TRUE(reference[0].has_solid());
  const double pole_range = reference[0].solid().range_m;
  EXPECT_NEAR(pole_range, 195.3 - std::sqrt(0.3 * 0.3 - 0.2 * 0.2), 1e-9);
  ASSERT_EQ(reference[0].wires().size(), 1u);
  const Candidate& visible = reference[0].wires()[0];
  EXPECT_LT(visible.range_m, pole_range);
  EXPECT_GT(visible.range_m, 185.0);
  EXPECT_NEAR(visible.incidence_deg, 89.5, 1e-6);
  // Without the pole the crossing segment at 200 m, head-on, is the candidate.
  objects.cylinders.clear();
  const EmbreeScene open(device, objects, ReceiverParams{}, kRegion, timeout_m());
  const auto unobstructed = trace_all(open, objects, rays);
  ASSERT_EQ(unobstructed[0].wires().size(), 1u);
  EXPECT_NEAR(unobstructed[0].wires()[0].range_m, 200.0, 1e-9);
  EXPECT_NEAR(unobstructed[0].wires()[0].incidence_deg, 0.0, 1e-9);
}

// Consecutive spans share their supports, so two poles may coincide: equal ranges go to the lower
// cylinder index, and a pole nearer by less than one float step still wins — in every API, as in
// the brute-force tracer.
TEST(EmbreeScene, CoincidentPolesAreDecidedInDouble) {
  Scene objects;
  objects.terrain.kind = TerrainKind::none;
  Cylinder pole;
  pole.id = "a/pole-2";
  pole.base_enu_m = Eigen::Vector3d(3.0, 800.0, 0.0);
  pole.radius_m = 0.4;
  pole.height_m = 30.0;
  objects.cylinders = {pole, pole, pole};  // 0 and 1 coincide
  objects.cylinders[1].id = "b/pole-1";
  objects.cylinders[2].id = "c/pole-1";
  objects.cylinders[2].base_enu_m.y() -= 1e-5;  // nearer by a third of a float step at 800 m
  std::vector<PulseRay> rays;
  for (int i = 0; i < 32; ++i) {
    rays.push_back(
        PulseRay{{3.0 + 0.35 * std::sin(i), 0.0, 1.0 + 0.8 * i}, Eigen::Vector3d::UnitY()});
  }
  const EmbreeDevice device;
  const EmbreeScene three(device, objects, ReceiverParams{}, kRegion, timeout_m());
  for (const PulseCandidates& pulse : trace_all(three, objects, rays)) {
    ASSERT_TRUE(pulse.has_solid());
    EXPECT_EQ(pulse.solid().object_index, 2u);
  }
  objects.cylinders.pop_back();
  const EmbreeScene two(device, objects, ReceiverParams{}, kRegion, timeout_m());
  for (const PulseCandidates& pulse : trace_all(two, objects, rays)) {
    ASSERT_TRUE(pulse.has_solid());
    EXPECT_EQ(pulse.solid().object_index, 0u);
  }
}

TEST(EmbreeScene, CylinderSilhouetteAndTopMatchTheExactIntersection) {
  Scene objects;
  objects.terrain.kind = TerrainKind::none;
  Cylinder pole;
  pole.id = "pole";
  pole.base_enu_m = Eigen::Vector3d(0.0, 900.0, 0.0);
  pole.radius_m = 0.3;
  pole.height_m = 25.0;
  Cylinder tree;
  tree.id = "tree";
  tree.surface = SurfaceClass::tree;
  tree.base_enu_m = Eigen::Vector3d(200.0, 200.0, 0.0);
  tree.radius_m = 3.0;
  tree.height_m = 12.0;
  objects.cylinders = {pole, tree};
  const EmbreeDevice device;
  const EmbreeScene scene(device, objects, ReceiverParams{}, kRegion, timeout_m());
  std::vector<PulseRay> rays;
  // Across the pole 900 m away at offsets up to and just past its radius.
  for (double offset : {0.0, 0.2, 0.299, 0.2999999, 0.3000001, 0.31}) {
    rays.push_back(PulseRay{{offset, 0.0, 10.0}, Eigen::Vector3d::UnitY()});
  }
  // Down onto the tree top from 150 m above, and a steep slant onto its wall.
  rays.push_back(PulseRay{{201.0, 201.0, 150.0}, -Eigen::Vector3d::UnitZ()});
  rays.push_back(PulseRay{{200.0, 100.0, 100.0}, Eigen::Vector3d(0.0, 1.0, -0.9).normalized()});
  const auto reference = trace_all(scene, objects, rays);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Cylinder& target = i < 6 ? objects.cylinders[0] : objects.cylinders[1];
    const auto hit = intersect(target, rays[i].origin_enu_m, rays[i].dir_enu, 0.0, timeout_m());
    ASSERT_EQ(reference[i].has_solid(), hit.has_value()) << i;
    if (!hit) continue;
    EXPECT_EQ(reference[i].solid().range_m, hit->t) << i;
    EXPECT_EQ(reference[i].solid().object_index, i < 6 ? 0u : 1u);
  }
  EXPECT_TRUE(reference[3].has_solid());
  EXPECT_FALSE(reference[4].has_solid());
  EXPECT_NEAR(reference[6].solid().range_m, 138.0, 1e-9);  // the top cap at 12 m
}

// Rays aimed exactly at terrain edges and corners (the flat plane's diagonal, the grid's lattice
// lines and vertices) from far away at 1–10° grazing: Embree must find the ground and the engine
// must report the same range as the double-precision brute force.
TEST(EmbreeScene, TerrainEdgesAndCornersAtGrazingIncidence) {
  test::Rng rng(11);
  for (bool grid : {false, true}) {
    Scene objects;
    objects.terrain = test::random_terrain(rng, grid, 1800.0);
    const EmbreeDevice device;
    const Eigen::AlignedBox2d region(Eigen::Vector2d(-1500.0, -1500.0),
                                     Eigen::Vector2d(1500.0, 1500.0));
    const EmbreeScene scene(device, objects, ReceiverParams{}, region, timeout_m());
    const TriangleMesh& mesh = scene.terrain_mesh();
    std::vector<PulseRay> rays;
    while (rays.size() < 400) {
      const auto& triangle = mesh.triangles[static_cast<std::size_t>(
          test::uniform_int(rng, 0, static_cast<int>(mesh.triangles.size()) - 1))];
      const Eigen::Vector3d& a = mesh.vertices[triangle[0]];
      const Eigen::Vector3d& b = mesh.vertices[triangle[1]];
      // A corner or a point on an edge, inside the region (its outer edges have no neighbour).
      const Eigen::Vector3d target =
          test::uniform(rng, 0.0, 1.0) < 0.3 ? a : a + test::uniform(rng, 0.0, 1.0) * (b - a);
      if (std::abs(target.x()) > 1400.0 || std::abs(target.y()) > 1400.0) continue;
      const double elevation = test::radians(test::uniform(rng, 1.0, 10.0));
      const double bearing = test::uniform(rng, 0.0, 2.0 * std::numbers::pi);
      const Eigen::Vector3d dir(std::cos(elevation) * std::sin(bearing),
                                std::cos(elevation) * std::cos(bearing), -std::sin(elevation));
      const double range = test::uniform(rng, 100.0, 1200.0);
      rays.push_back(PulseRay{target - range * dir, dir});
    }
    const auto reference = trace_all(scene, objects, rays);
    int hits = 0;
    for (const PulseCandidates& pulse : reference) hits += pulse.has_solid() ? 1 : 0;
    EXPECT_EQ(hits, 400);
  }
}

}  // namespace
}  // namespace owsim
