// Keyed random draws (geometry/keyed_random.hpp): the standard normal every detected return
// draws for its range noise, against the Philox block alone (the floor) and the Box–Muller
// transform owsim used before the ziggurat. Items are draws; each draw has its own pulse key.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "geometry/keyed_random.hpp"

namespace owsim {
namespace {

RandomKey pulse_key(std::int64_t pulse) {
  return {2024, 3, pulse, RandomPurpose::range_noise_first};
}

void BM_RandomBlock(benchmark::State& state) {
  std::int64_t pulse = 0;
  for (auto _ : state) benchmark::DoNotOptimize(random_block(pulse_key(pulse++)));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RandomBlock);

void BM_StandardNormal(benchmark::State& state) {
  std::int64_t pulse = 0;
  for (auto _ : state) benchmark::DoNotOptimize(standard_normal(pulse_key(pulse++)));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_StandardNormal);

// FOR COMPARISON ONLY, not used by owsim: the previous standard_normal, Box–Muller on the two
// 53-bit uniforms of the key's block, sqrt(−2 log u1) · cos(2π u2).
double box_muller_normal(const RandomKey& key) {
  const PhiloxBlock block = random_block(key);
  const auto unit = [](std::uint32_t high, std::uint32_t low) {
    return static_cast<double>(((static_cast<std::uint64_t>(high) << 32) | low) >> 11) * 0x1.0p-53;
  };
  const double u1 = 1.0 - unit(block[0], block[1]);
  const double u2 = unit(block[2], block[3]);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

void BM_BoxMuller(benchmark::State& state) {
  std::int64_t pulse = 0;
  for (auto _ : state) benchmark::DoNotOptimize(box_muller_normal(pulse_key(pulse++)));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BoxMuller);

}  // namespace
}  // namespace owsim
