#pragma once
// Counter-based random numbers keyed by (scenario seed, frame, pulse, purpose).
//
// Every random draw in owsim is a pure function of its key, so a frame can be simulated alone,
// on any thread or machine, and give the same bytes (DESIGN.md "Determinism"). The generator is
// Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011): the key
// is the 64-bit seed, the 128-bit counter is (frame: words 0-1, pulse low 32 bits: word 2,
// purpose | pulse high 24 bits << 8: word 3). Uniforms carry 53 random bits.
//
// Normals use the ziggurat method (Marsaglia & Tsang, "The ziggurat method for generating random
// variables", J. Stat. Softw. 5(8), 2000) on the half-normal with 256 layers, the layer index and
// the uniform taken from separate bits (Doornik, "An improved ziggurat method", 2005). The key's
// block gives the layer (8 bits), the sign (1 bit), the 53-bit uniform and the wedge uniform;
// about 98.5 % of draws end there with a table look-up, a multiply and a compare. A rejection in
// a wedge (an exp) starts again on the next block; the tail |z| > r = 3.654…, about 1 draw in
// 3,900, uses Marsaglia's exponential method (two logs per try). Those blocks are
// normal_extra_block(key, 0), (key, 1), … in turn. The draw is exact N(0, 1) up to double
// rounding: the tables are computed from exp and erfc on first use (r to the last bit, strip
// areas equal to 1e-12 relative: a probability error below 1e-14), and a value lies on a grid of
// at most 4.4e-16.
#include <array>
#include <cstdint>
#include <span>

namespace owsim {

// What a draw is for. Each purpose is its own stream: never reuse a value for two purposes.
// Values stay below 0x80: bit 7 of the counter's purpose byte marks normal_extra_block.
enum class RandomPurpose : std::uint32_t {
  frame_jitter = 1,       // SENSOR-SPEC §2 frame-start β jitter
  range_noise_first,      // §1 range noise of return 1
  range_noise_second,     // §1 range noise of return 2
  range_noise_reference,  // §8 reference-fiber range noise
  irs_error,              // §5 IRS error model, per navigation record
  irs_bias,               // §5 IRS per-flight bias
  forest_layout,          // forest generator, per tree
  sweep_draw,             // a sweep member's varied value (io/sweep/sweep_file.hpp)
  echo_detection,         // §11 whether a candidate echo registers; pulse | object << 32
  false_trigger,          // §11 a pulse's false triggers; pulse | draw index << 32
  false_trigger_group,    // §11 pulses 128j..128j+127's smallest first exponential; key pulse j
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
// The key's further blocks, used only by standard_normal when its first block is rejected or
// falls in the tail: the key's counter with bit 7 of the purpose byte set (so never a
// random_block of any key), under the Philox key seed XOR index · 0x9E3779B97F4A7C15.
[[nodiscard]] PhiloxBlock normal_extra_block(const RandomKey& key, std::uint32_t index);
// Uniform in [0, 1), 53 bits.
[[nodiscard]] double uniform01(const RandomKey& key);
// Uniform in [-1, 1).
[[nodiscard]] double uniform_pm1(const RandomKey& key);
// Standard normal N(0, 1), by the ziggurat above.
[[nodiscard]] double standard_normal(const RandomKey& key);
// The same draw when random_block(key) is already known (random_blocks below): `first` must be
// that block. The same value, bit for bit.
[[nodiscard]] double standard_normal(const RandomKey& key, const PhiloxBlock& first);

// standard_normal(key, blocks[i]) for every i whose draw ends in its first block's rectangle
// (about 98.5 %: a table look-up, a multiply and a compare, over arrays), NaN for the others, which
// the caller draws with standard_normal. The same value, bit for bit.
void first_block_normals(std::span<const PhiloxBlock> blocks, std::span<double> out);
// random_block of the keys (seed, frame, first_pulse + i, purpose) for every i < out.size(), the
// same bits, computed for many pulses at once over vector lanes (AVX2 where the CPU has it): the
// per-pulse draws of a block of pulses, batched.
void random_blocks(std::uint64_t seed, std::int64_t frame, std::int64_t first_pulse,
                   RandomPurpose purpose, std::span<PhiloxBlock> out);
// The same for the keys (seed, frame, pulses[i], purpose), any pulses in any order: only the
// draws a caller needs (pulses.size() == out.size(), else owsim::Error).
void random_blocks(std::uint64_t seed, std::int64_t frame, std::span<const std::int64_t> pulses,
                   RandomPurpose purpose, std::span<PhiloxBlock> out);

}  // namespace owsim
