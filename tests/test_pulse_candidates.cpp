// Protects the per-surface rules both tracers share (sensor/pulse_candidates.hpp, SENSOR-SPEC §7
// "Pinned per surface", "Pinned occlusion"): the wire, cylinder and ground candidates carry the
// §7 energies; a pulse keeps each conductor's strongest segment whatever the order segments are
// offered in; gather() drops wires at or beyond the solid hit, keeps nearer ones, and a solid
// below the threshold still occludes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include "sensor/pulse_candidates.hpp"
#include "sensor/reflectivity.hpp"
#include "sensor/return_energy.hpp"

namespace owsim {
namespace {

Candidate wire(std::uint32_t object, double range_m, double energy) {
  return Candidate{range_m, energy, 10.0, object, static_cast<std::uint8_t>(SurfaceClass::wire)};
}

Candidate solid(std::uint32_t object, double range_m, double energy) {
  return Candidate{range_m, energy, 20.0, object, static_cast<std::uint8_t>(SurfaceClass::pole)};
}

// A horizontal east–west conductor at height 0, from e = −50 to e = 50 in two segments.
Conductor straight_conductor(double radius_m) {
  Conductor conductor;
  conductor.id = "span/1";
  conductor.points_enu_m = {{-50.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {50.0, 0.0, 0.0}};
  conductor.radius_m = radius_m;
  conductor.reflectivity = 0.4;
  return conductor;
}

TEST(WireSegmentCandidate, HeadOnCarriesTheSpecEnergyAndRange) {
  const ReceiverParams receiver;
  const Conductor conductor = straight_conductor(0.01);
  // Looking north at the wire 200 m away, passing 0.03 m above its axis.
  const PulseRay ray{{10.0, -200.0, 0.03}, Eigen::Vector3d::UnitY()};
  Candidate candidate;
  ASSERT_TRUE(wire_segment_candidate(ray, conductor, 1, 7, receiver, candidate));
  EXPECT_NEAR(candidate.range_m, 200.0, 1e-12);
  EXPECT_NEAR(candidate.incidence_deg, 0.0, 1e-12);
  EXPECT_EQ(candidate.object_index, 7u);
  EXPECT_EQ(candidate.surface, static_cast<std::uint8_t>(SurfaceClass::wire));
  const ReturnEnergy expected =
      wire_return_energy(0.03, 200.0, 0.01, 0.0, 0.4, receiver.beam, receiver.atmosphere);
  EXPECT_DOUBLE_EQ(candidate.energy_rel, expected.energy_rel);
  EXPECT_GT(candidate.energy_rel, 0.0);
  // The other segment is west of e = 0: its closest point is its end, 10 m off the ray.
  EXPECT_FALSE(wire_segment_candidate(ray, conductor, 0, 7, receiver, candidate));
}

TEST(WireSegmentCandidate, CaptureEndsAtWireRadiusPlusBeamRadius) {
  const ReceiverParams receiver;  // 1 mrad: r_beam(400 m) = 0.2 m
  const Conductor conductor = straight_conductor(0.01);
  const double limit = 0.01 + beam_radius_m(400.0, receiver.beam);
  Candidate candidate;
  const PulseRay inside{{5.0, -400.0, limit * (1.0 - 1e-9)}, Eigen::Vector3d::UnitY()};
  EXPECT_TRUE(wire_segment_candidate(inside, conductor, 1, 0, receiver, candidate));
  EXPECT_GT(candidate.energy_rel, 0.0);
  EXPECT_LT(candidate.energy_rel, 1e-9);  // a sliver of the beam
  const PulseRay outside{{5.0, -400.0, limit * (1.0 + 1e-9)}, Eigen::Vector3d::UnitY()};
  EXPECT_FALSE(wire_segment_candidate(outside, conductor, 1, 0, receiver, candidate));
}

TEST(WireSegmentCandidate, IncidenceIsToTheWireNormal) {
  const ReceiverParams receiver;
  const Conductor conductor = straight_conductor(0.01);
  const double angle = 30.0 * std::numbers::pi / 180.0;  // 30° off the wire's normal
  const Eigen::Vector3d dir(std::sin(angle), std::cos(angle), 0.0);
  const PulseRay ray{Eigen::Vector3d(20.0, 0.0, 0.0) - 100.0 * dir, dir};
  Candidate candidate;
  ASSERT_TRUE(wire_segment_candidate(ray, conductor, 1, 0, receiver, candidate));
  EXPECT_NEAR(candidate.incidence_deg, 30.0, 1e-9);
  EXPECT_NEAR(candidate.range_m, 100.0, 1e-9);
  const ReturnEnergy expected =
      wire_return_energy(0.0, 100.0, 0.01, 30.0, 0.4, receiver.beam, receiver.atmosphere);
  EXPECT_NEAR(candidate.energy_rel, expected.energy_rel, 1e-12 * expected.energy_rel);
}

TEST(CylinderCandidate, WallAndTopCap) {
  const ReceiverParams receiver;
  Cylinder pole;
  pole.surface = SurfaceClass::tree;
  pole.radius_m = 2.0;
  pole.reflectivity = 0.3;
  const PulseRay ray{{0.0, -100.0, 5.0}, Eigen::Vector3d::UnitY()};
  CylinderHit wall{98.0, -Eigen::Vector3d::UnitY(), 0.0, CylinderFace::wall};
  const Candidate on_wall = cylinder_candidate(ray, pole, wall, 3, receiver);
  EXPECT_EQ(on_wall.surface, static_cast<std::uint8_t>(SurfaceClass::tree));
  EXPECT_EQ(on_wall.object_index, 3u);
  EXPECT_DOUBLE_EQ(on_wall.range_m, 98.0);
  // The whole beam on the silhouette: fraction 1, head-on, 0.3 · 0.95.
  EXPECT_NEAR(on_wall.energy_rel, 0.3 * 0.95, 1e-12);
  // Near the silhouette edge the strip covers part of the beam.
  wall.axis_distance_m = 1.99;
  const Candidate near_edge = cylinder_candidate(ray, pole, wall, 3, receiver);
  EXPECT_LT(near_edge.energy_rel, on_wall.energy_rel);
  // A top-cap hit sees a disc: the axis distance does not reduce the footprint.
  const PulseRay down{{1.99, 0.0, 100.0}, -Eigen::Vector3d::UnitZ()};
  const CylinderHit top{90.0, Eigen::Vector3d::UnitZ(), 1.99, CylinderFace::top};
  EXPECT_NEAR(cylinder_candidate(down, pole, top, 3, receiver).energy_rel, 0.3 * 0.95, 1e-12);
}

TEST(GroundCandidate, UsesTheTerrainNormalAndReflectivity) {
  const ReceiverParams receiver;
  const double angle = 60.0 * std::numbers::pi / 180.0;  // 60° from the vertical
  const PulseRay ray{{0.0, 0.0, 100.0}, Eigen::Vector3d(0.0, std::sin(angle), -std::cos(angle))};
  const Candidate ground =
      ground_candidate(ray, 200.0, Eigen::Vector3d::UnitZ(), 0.2, 11, receiver);
  EXPECT_NEAR(ground.incidence_deg, 60.0, 1e-9);
  EXPECT_EQ(ground.surface, static_cast<std::uint8_t>(SurfaceClass::ground));
  EXPECT_NEAR(ground.energy_rel, reflectivity_pct(60.0) / 40.0 * 0.2 * 0.95, 1e-12);
}

TEST(PulseCandidates, KeepsEachConductorsStrongestSegment) {
  PulseCandidates pulse;
  pulse.offer_wire(wire(0, 100.0, 0.01));
  pulse.offer_wire(wire(1, 300.0, 0.2));
  pulse.offer_wire(wire(0, 101.0, 0.05));  // stronger: replaces
  pulse.offer_wire(wire(0, 99.0, 0.02));   // weaker: ignored
  ASSERT_EQ(pulse.wires().size(), 2u);
  EXPECT_DOUBLE_EQ(pulse.wires()[0].range_m, 101.0);
  EXPECT_DOUBLE_EQ(pulse.wires()[0].energy_rel, 0.05);
  EXPECT_DOUBLE_EQ(pulse.wires()[1].energy_rel, 0.2);
  // Equal energies keep the nearer segment.
  pulse.offer_wire(wire(1, 299.0, 0.2));
  pulse.offer_wire(wire(1, 301.0, 0.2));
  EXPECT_DOUBLE_EQ(pulse.wires()[1].range_m, 299.0);
  pulse.clear();
  EXPECT_TRUE(pulse.wires().empty());
  EXPECT_FALSE(pulse.has_solid());
}

// The kept set, sorted by object, as a comparable list.
std::vector<std::pair<std::uint32_t, double>> kept(const PulseCandidates& pulse) {
  std::vector<std::pair<std::uint32_t, double>> result;
  for (const Candidate& c : pulse.wires()) result.emplace_back(c.object_index, c.energy_rel);
  std::sort(result.begin(), result.end());
  return result;
}

TEST(PulseCandidates, ResultDoesNotDependOnOfferOrder) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> energy(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    // Up to 12 conductors (more than kMaxWires), 1–6 segments each, distinct energies.
    const int conductors = 1 + trial % 12;
    std::vector<Candidate> offers;
    std::vector<double> best(static_cast<std::size_t>(conductors), 0.0);
    for (int c = 0; c < conductors; ++c) {
      const int segments = 1 + static_cast<int>(rng() % 6);
      for (int s = 0; s < segments; ++s) {
        const double e = energy(rng);
        offers.push_back(wire(static_cast<std::uint32_t>(c), 100.0 + c + 0.1 * s, e));
        best[static_cast<std::size_t>(c)] = std::max(best[static_cast<std::size_t>(c)], e);
      }
    }
    PulseCandidates reference;
    for (const Candidate& offer : offers) reference.offer_wire(offer);
    const auto expected = kept(reference);

    // The kept set is the kMaxWires conductors with the highest best-segment energy.
    std::vector<std::pair<double, std::uint32_t>> ranking;
    for (int c = 0; c < conductors; ++c)
      ranking.emplace_back(best[static_cast<std::size_t>(c)], static_cast<std::uint32_t>(c));
    std::sort(ranking.rbegin(), ranking.rend());
    ranking.resize(std::min<std::size_t>(ranking.size(), PulseCandidates::kMaxWires));
    std::vector<std::pair<std::uint32_t, double>> strongest;
    for (const auto& [e, c] : ranking) strongest.emplace_back(c, e);
    std::sort(strongest.begin(), strongest.end());
    ASSERT_EQ(expected, strongest) << "trial " << trial;

    for (int shuffle = 0; shuffle < 10; ++shuffle) {
      std::shuffle(offers.begin(), offers.end(), rng);
      PulseCandidates pulse;
      for (const Candidate& offer : offers) pulse.offer_wire(offer);
      ASSERT_EQ(kept(pulse), expected) << "trial " << trial << " shuffle " << shuffle;
    }
  }
}

TEST(PulseCandidates, GatherDropsWiresBeyondTheSolidAndKeepsNearerOnes) {
  PulseCandidates pulse;
  pulse.offer_wire(wire(0, 150.0, 0.1));
  pulse.offer_wire(wire(1, 250.0, 0.1));
  pulse.offer_wire(wire(2, 200.0, 0.1));  // exactly at the solid: behind its surface
  pulse.set_solid(solid(5, 200.0, 0.3));
  std::array<Candidate, PulseCandidates::kMaxWires + 1> buffer;
  const auto gathered = pulse.gather(buffer);
  ASSERT_EQ(gathered.size(), 2u);
  EXPECT_EQ(gathered[0].object_index, 0u);
  EXPECT_EQ(gathered[1].object_index, 5u);  // the solid comes last
  EXPECT_TRUE(pulse.has_solid());
  EXPECT_EQ(pulse.solid().object_index, 5u);

  PulseCandidates no_solid;
  no_solid.offer_wire(wire(0, 150.0, 0.1));
  no_solid.offer_wire(wire(1, 1000.0, 0.1));
  EXPECT_EQ(no_solid.gather(buffer).size(), 2u);
}

TEST(PulseCandidates, SolidBelowTheThresholdStillOccludes) {
  ReceiverParams receiver;
  receiver.range_noise_sigma_m = 0.0;
  PulseCandidates pulse;
  pulse.offer_wire(wire(0, 150.0, 0.2));  // strong wire behind a dark pole
  pulse.offer_wire(wire(1, 80.0, 0.05));  // a wire in front of it
  pulse.set_solid(solid(2, 120.0, 0.5 * receiver.threshold));
  std::array<Candidate, PulseCandidates::kMaxWires + 1> buffer;
  const auto gathered = pulse.gather(buffer);
  ASSERT_EQ(gathered.size(), 2u);
  const PulseReturns returns = select_returns(gathered, receiver, 1, 0, 0);
  ASSERT_EQ(returns.count, 1);  // only the wire in front: the dark pole is not detected
  EXPECT_EQ(returns.returns[0].object_index, 1u);
  EXPECT_NEAR(returns.returns[0].range_m, 80.0, 1e-12);
}

}  // namespace
}  // namespace owsim
