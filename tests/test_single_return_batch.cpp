// The receiver's common case over arrays (sensor/single_return_batch.hpp) against the one-pulse
// path it stands for: every pulse the batch decides gets select_single_return's returns bit for
// bit, over ranges and energies around every boundary the arithmetic meets — the threshold, the
// sure-detection margin, the counter's rounding and timeout, non-finite values — with the
// receiver's noise on and off and the range noise on and off.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "geometry/keyed_random.hpp"
#include "sensor/receiver.hpp"
#include "sensor/single_return_batch.hpp"

namespace owsim {
namespace {

constexpr std::uint64_t kSeed = 0x5EED;
constexpr std::int64_t kBatchFrame = 31;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// A pulse's candidate: ranges across the gate and its edges, on and next to the counter's
// rounding boundaries; energies across the threshold and the sure-detection margin.
Candidate candidate_for(int pulse, std::mt19937_64& random, const ReceiverParams& p) {
  const double per_count = range_per_count_m(p.counter);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double range = 1300.0 * unit(random);
  switch (pulse % 11) {
    case 0:
      range = (std::floor(range / per_count) + 0.5) * per_count;  // a rounding boundary
      break;
    case 1:
      range = std::nextafter((std::floor(range / per_count) + 0.5) * per_count, 0.0);
      break;
    case 2:
      range = (p.counter.timeout_counts - 0.5) * per_count + (unit(random) - 0.5);  // timeout
      break;
    case 3:
      range = pulse % 3 == 0 ? 0.0 : (pulse % 3 == 1 ? -0.0 : 0.3 * unit(random));
      break;
    default:
      break;
  }
  double energy = p.threshold * (0.5 + 1.5 * unit(random));
  if (pulse % 97 == 5) energy = p.threshold;
  if (pulse % 89 == 7) energy = std::numeric_limits<double>::quiet_NaN();
  if (pulse % 83 == 9) energy = std::numeric_limits<double>::infinity();
  if (pulse % 79 == 11) range = std::numeric_limits<double>::quiet_NaN();
  if (pulse % 73 == 13) range = std::numeric_limits<double>::infinity();
  return Candidate{range, energy, 7.5 + pulse % 40, static_cast<std::uint32_t>(pulse % 13),
                   static_cast<std::uint8_t>(pulse % 5)};
}

struct Tally {
  int one_return = 0, no_return = 0, undecided = 0;
};

// Runs of 256 pulses through the batch, each decided pulse against select_single_return.
// (void: gtest's ASSERT returns from the function)
void check(const ReceiverParams& p, int pulses, Tally& tally) {
  const ReceiverNoise noise = receiver_noise(p);
  SingleReturnBatch batch(p, noise.on());
  std::mt19937_64 random(static_cast<std::uint64_t>(pulses) ^ bits(p.range_noise_sigma_m));
  // Backgrounds a pulse of a group without a trigger can have (at night 0; off, any).
  const double most = noise.on() ? noise.max_background() : 1.3;
  const double backgrounds[] = {0.0, 0.4 * most, most};
  for (int run = 0; run < pulses; run += 256) {
    std::vector<PhiloxBlock> blocks(256);
    std::vector<double> normals(256);
    random_blocks(kSeed, kBatchFrame, run, RandomPurpose::range_noise_first, blocks);
    first_block_normals(blocks, normals);
    std::vector<Candidate> candidates;
    std::vector<int> pulse_of;
    batch.clear();
    for (int k = run; k < run + 256; ++k) {
      const double background = backgrounds[k % 3];
      // With the noise on, only pulses of a group without a false trigger reach the batch.
      if (noise.on() && !noise.group_has_no_trigger(background, kSeed, kBatchFrame, k)) continue;
      candidates.push_back(candidate_for(k, random, p));
      pulse_of.push_back(k);
      batch.add(candidates.back(), background, normals[static_cast<std::size_t>(k - run)]);
    }
    batch.evaluate();
    for (std::size_t slot = 0; slot < batch.size(); ++slot) {
      const int k = pulse_of[slot];
      if (batch.outcome(slot) == SingleReturnBatch::Outcome::undecided) {
        ++tally.undecided;
        continue;
      }
      const PhiloxBlock& block = blocks[static_cast<std::size_t>(k - run)];
      PulseNoise pulse_noise{noise.on() ? &noise : nullptr, backgrounds[k % 3], {}, &block};
      PulseReturns expected, got;
      // Different leftovers in the unused entries: only the counted ones may matter.
      expected.returns[0].range_m = 1.0;
      got.returns[0].range_m = 2.0;
      select_single_return(candidates[slot], p, kSeed, kBatchFrame, k, expected, pulse_noise);
      batch.write(slot, candidates[slot], got);
      (got.count == 1 ? tally.one_return : tally.no_return) += 1;
      ASSERT_EQ(got.count, expected.count) << k;
      ASSERT_EQ(got.counter1, expected.counter1) << k;
      ASSERT_EQ(got.counter2, expected.counter2) << k;
      if (got.count == 1) {
        const Return& a = got.returns[0];
        const Return& b = expected.returns[0];
        ASSERT_EQ(bits(a.range_m), bits(b.range_m)) << k;
        ASSERT_EQ(bits(a.energy_rel), bits(b.energy_rel)) << k;
        ASSERT_EQ(bits(a.incidence_deg), bits(b.incidence_deg)) << k;
        ASSERT_EQ(bits(a.true_range_m), bits(b.true_range_m)) << k;
        ASSERT_EQ(a.object_index, b.object_index) << k;
        ASSERT_EQ(a.counter, b.counter) << k;
        ASSERT_EQ(a.surface, b.surface) << k;
      }
    }
  }
}

TEST(SingleReturnBatch, DecidesAsTheOnePulsePathWithTheNoiseOn) {
  ReceiverParams p;
  p.threshold = 0.005;
  p.noise.noise_at_1km = 0.0006;  // echoes within 8.5 σ_n of T at a few hundred metres
  Tally tally;
  check(p, 40'000, tally);
  EXPECT_GT(tally.one_return, 10'000);
  EXPECT_GT(tally.no_return, 3'000);
  // Echoes near the threshold, normals past the first rectangle, counts on a boundary.
  EXPECT_GT(tally.undecided, 1'000);
  EXPECT_LT(tally.undecided, 30'000);
}

TEST(SingleReturnBatch, DecidesAsTheOnePulsePathWithTheNoiseOff) {
  ReceiverParams p;
  p.noise.on = false;
  Tally tally;
  check(p, 20'000, tally);
  EXPECT_GT(tally.one_return, 8'000);
  EXPECT_GT(tally.no_return, 3'000);
  EXPECT_GT(tally.undecided, 100);  // the normals the ziggurat rejects, the rounding boundaries
  EXPECT_LT(tally.undecided, 4'000);
}

TEST(SingleReturnBatch, DecidesAsTheOnePulsePathWithoutRangeNoise) {
  for (const bool noisy : {false, true}) {
    ReceiverParams p;
    p.noise.on = noisy;
    p.range_noise_sigma_m = 0.0;
    Tally tally;
    check(p, 10'000, tally);
    EXPECT_GT(tally.one_return, 2'000) << noisy;
    EXPECT_GT(tally.no_return, 500) << noisy;
  }
}

}  // namespace
}  // namespace owsim
