#pragma once
// Counter-based random numbers keyed by (scenario seed, frame, pulse, purpose).
//
// Every random draw in owsim is a pure function of its key, so a frame can be simulated alone,
// on any thread or machine, and give the same bytes (DESIGN.md "Determinism"). The generator is
// Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011): the key
// is the 64-bit seed, the 128-bit counter is (frame, pulse, purpose). Uniforms carry 53 random
// bits; normals use Box-Muller on the two uniforms of one block.
#include <array>
#include <cstdint>

namespace owsim {

// What a draw is for. Each purpose is its own stream: never reuse a value for two purposes.
enum class RandomPurpose : std::uint32_t {
  frame_jitter = 1,      // SENSOR-SPEC §2 frame-start β jitter
  range_noise_first,     // §1 range noise of return 1
  range_noise_second,    // §1 range noise of return 2
  range_noise_reference, // §8 reference-fiber range noise
  irs_error,             // §5 IRS error model, per navigation record
  irs_bias,              // §5 IRS per-flight bias
  forest_layout,         // forest generator, per tree
};

using PhiloxBlock = std::array<std::uint32_t, 4>;

// One Philox4x32-10 block: 128 random bits for (counter, key).
[[nodiscard]] PhiloxBlock philox4x32_10(PhiloxBlock counter, std::array<std::uint32_t, 2> key);

struct RandomKey {
  std::uint64_t seed = 0;
  std::int64_t frame = 0;
  std::int64_t pulse = 0;
  RandomPurpose purpose = RandomPurpose::frame_jitter;
};

// The 128 bits of a key's block.
[[nodiscard]] PhiloxBlock random_block(const RandomKey& key);
// Uniform in [0, 1), 53 bits.
[[nodiscard]] double uniform01(const RandomKey& key);
// Uniform in [-1, 1).
[[nodiscard]] double uniform_pm1(const RandomKey& key);
// Standard normal N(0, 1).
[[nodiscard]] double standard_normal(const RandomKey& key);

}  // namespace owsim
