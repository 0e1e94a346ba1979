// Protects the batch the tracer evaluates a chunk's solid hits in
// (sensor/surface_energy_batch.hpp): every slot gets exactly the bits the single-hit path gives
// (the brute-force tracer's and the engine's candidates must agree to the bit), over random
// directions, normals and grazing hits.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sensor/reflectivity.hpp"
#include "sensor/return_energy.hpp"
#include "sensor/surface_energy_batch.hpp"

namespace owsim {
namespace {

Eigen::Vector3d random_unit(std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
}

TEST(SurfaceEnergyBatch, EverySlotIsTheSingleHitsBits) {
  std::mt19937_64 random(4646);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SurfaceEnergyBatch batch;
  std::vector<SurfaceTerms> terms;
  for (int round = 0; round < 20; ++round) {
    batch.clear();
    terms.clear();
    const std::size_t count = round == 0 ? SurfaceEnergyBatch::kCapacity
                                         : static_cast<std::size_t>(unit(random) * 200.0) + 1;
    for (std::size_t i = 0; i < count; ++i) {
      SurfaceTerms hit;
      hit.ray_dir = random_unit(random);
      hit.normal = random_unit(random);
      if (i % 7 == 0) {  // grazing: the normal almost across the ray
        hit.normal = (hit.normal - hit.normal.dot(hit.ray_dir) * hit.ray_dir).normalized();
        hit.normal += 1e-9 * hit.ray_dir;
      }
      if (i % 11 == 0) hit.normal = hit.ray_dir;  // head on
      hit.footprint_fraction = i % 3 == 0 ? 1.0 : unit(random);
      hit.reflectivity = unit(random);
      hit.transmission = 0.5 + 0.5 * unit(random);
      EXPECT_EQ(batch.add(hit), i);
      terms.push_back(hit);
    }
    batch.evaluate();
    ASSERT_EQ(batch.size(), count);
    for (std::size_t i = 0; i < count; ++i) {
      const AngleEnergy single = surface_angle_energy(terms[i]);
      const AngleEnergy batched = batch.result(i);
      ASSERT_EQ(batched.incidence_deg, single.incidence_deg) << "slot " << i;
      ASSERT_EQ(batched.energy_rel, single.energy_rel) << "slot " << i;
      // And the §7 numbers: θ from the vectors, energy by eq 7.13.
      const double theta = surface_incidence_deg(terms[i].ray_dir, terms[i].normal);
      EXPECT_EQ(single.incidence_deg, theta);
      EXPECT_EQ(single.energy_rel, energy_rel(terms[i].footprint_fraction, theta,
                                              terms[i].reflectivity, terms[i].transmission));
    }
  }
}

TEST(SurfaceEnergyBatch, PinnedValues) {
  SurfaceEnergyBatch batch;
  SurfaceTerms down;  // straight down on level ground: θ = 0, Ref(0)/40 = 1
  down.ray_dir = {0, 0, -1};
  down.normal = {0, 0, 1};
  down.reflectivity = 0.2;
  down.transmission = 0.95;
  SurfaceTerms slant = down;  // 60° from the normal: Ref(60°) = Ref(45°)·30/45 (eq 7.12)
  slant.ray_dir = {std::sin(60.0 * M_PI / 180.0), 0, -std::cos(60.0 * M_PI / 180.0)};
  batch.add(down);
  batch.add(slant);
  batch.evaluate();
  EXPECT_EQ(batch.result(0).incidence_deg, 0.0);
  EXPECT_NEAR(batch.result(0).energy_rel, 0.2 * 0.95, 1e-15);
  EXPECT_NEAR(batch.result(1).incidence_deg, 60.0, 1e-12);
  EXPECT_NEAR(batch.result(1).energy_rel, 8.07 * 30.0 / 45.0 / 40.0 * 0.2 * 0.95, 2e-5);
}

TEST(SurfaceEnergyBatch, RefusesMoreThanItsCapacity) {
  SurfaceEnergyBatch batch;
  for (std::size_t i = 0; i < SurfaceEnergyBatch::kCapacity; ++i) batch.add(SurfaceTerms{});
  EXPECT_THROW(batch.add(SurfaceTerms{}), std::exception);
}

}  // namespace
}  // namespace owsim
