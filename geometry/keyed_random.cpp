#include "geometry/keyed_random.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/error.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace owsim {
namespace {

constexpr std::uint32_t kMultiplier0 = 0xD2511F53u;
constexpr std::uint32_t kMultiplier1 = 0xCD9E8D57u;
constexpr std::uint32_t kWeyl0 = 0x9E3779B9u;  // golden ratio
constexpr std::uint32_t kWeyl1 = 0xBB67AE85u;  // sqrt(3) - 1

constexpr std::uint32_t kExtraBlockFlag = 0x80u;  // bit 7 of the counter's purpose byte
static_assert(static_cast<std::uint32_t>(RandomPurpose::forest_layout) < kExtraBlockFlag);
constexpr std::uint64_t kExtraKeyStep = 0x9E3779B97F4A7C15u;  // 2⁶⁴ / golden ratio

void mulhilo(std::uint32_t a, std::uint32_t b, std::uint32_t& hi, std::uint32_t& lo) {
  const std::uint64_t product = static_cast<std::uint64_t>(a) * b;
  hi = static_cast<std::uint32_t>(product >> 32);
  lo = static_cast<std::uint32_t>(product);
}

std::uint64_t join(std::uint32_t high, std::uint32_t low) {
  return (static_cast<std::uint64_t>(high) << 32) | low;
}

// The top 53 of 64 random bits as a double in [0, 1).
double unit_interval(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

// 53 random bits from two 32-bit words, as a double in [0, 1).
double unit_interval(std::uint32_t high, std::uint32_t low) {
  return unit_interval(join(high, low));
}

PhiloxBlock counter_of(const RandomKey& key) {
  const auto frame = static_cast<std::uint64_t>(key.frame);
  const auto pulse = static_cast<std::uint64_t>(key.pulse);
  return {static_cast<std::uint32_t>(frame), static_cast<std::uint32_t>(frame >> 32),
          static_cast<std::uint32_t>(pulse),
          static_cast<std::uint32_t>(key.purpose) | (static_cast<std::uint32_t>(pulse >> 32) << 8)};
}

std::array<std::uint32_t, 2> philox_key(std::uint64_t seed) {
  return {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)};
}

// The ziggurat of the half-normal density f(x) = exp(−x²/2), x ≥ 0 (Marsaglia & Tsang 2000):
// kLayers strips of equal area v. Strip 0 is the base rectangle [0, r] × [0, f(r)] plus the tail
// x > r, drawn as a rectangle of width edge[0] = v / f(r); strip i ≥ 1 is [0, edge[i]] ×
// [f(edge[i]), f(edge[i + 1])], with edge[1] = r and edge[kLayers] = 0.
constexpr std::size_t kLayers = 256;

struct Ziggurat {
  std::array<double, kLayers + 1> edge{};    // x_i, decreasing
  std::array<double, kLayers + 1> height{};  // f(x_i); height[0] = 0, the base strip's floor
  double r = 0.0;                            // where the tail starts
};

double half_normal_density(double x) { return std::exp(-0.5 * x * x); }

// Stacks equal-area strips on the base strip of tail start r (edge[1] = r … edge[kLayers − 1])
// and returns by how much the last strip's top, f(edge[kLayers − 1]) + v / edge[kLayers − 1],
// overshoots the peak f(0) = 1: positive when r is too small, negative when too large.
double stack_strips(double r, Ziggurat& z) {
  const double tail_area = std::sqrt(std::numbers::pi / 2.0) * std::erfc(r / std::numbers::sqrt2);
  const double v = r * half_normal_density(r) + tail_area;
  z.r = r;
  z.edge[0] = v / half_normal_density(r);
  z.edge[1] = r;
  for (std::size_t i = 1; i + 1 < kLayers; ++i) {
    const double top = half_normal_density(z.edge[i]) + v / z.edge[i];
    if (top >= 1.0) return top - 1.0;  // past the peak before the last strip
    z.edge[i + 1] = std::sqrt(-2.0 * std::log(top));
  }
  return half_normal_density(z.edge[kLayers - 1]) + v / z.edge[kLayers - 1] - 1.0;
}

// Bisects for the r that closes the stack at the peak, to the last bit of a double (1 ulp from the
// 3.6541528853610088 other 256-layer ziggurats tabulate); the top strip's area then matches v to
// 1e-12 (the stack amplifies r's rounding), a probability error below 1e-14.
Ziggurat build_ziggurat() {
  Ziggurat z;
  double too_small = 2.0, too_large = 5.0;
  for (;;) {
    const double mid = 0.5 * (too_small + too_large);
    if (mid <= too_small || mid >= too_large) break;
    (stack_strips(mid, z) > 0.0 ? too_small : too_large) = mid;
  }
  stack_strips(too_large, z);
  z.edge[kLayers] = 0.0;
  for (std::size_t i = 1; i <= kLayers; ++i) z.height[i] = half_normal_density(z.edge[i]);
  return z;
}

const Ziggurat& ziggurat() {
  static const Ziggurat z = build_ziggurat();
  return z;
}

// The blocks standard_normal reads after the key's own.
class ExtraBlocks {
 public:
  explicit ExtraBlocks(const RandomKey& key) : key_(key) {}
  PhiloxBlock next() { return normal_extra_block(key_, index_++); }

 private:
  const RandomKey& key_;
  std::uint32_t index_ = 0;
};

// x with its sign bit flipped when `sign` (0 or bit 63) is set: no branch on a coin flip.
double signed_by(double x, std::uint64_t sign) {
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) ^ sign);
}

// |z| beyond r: Marsaglia's exponential method (Marsaglia 1964; Marsaglia & Tsang 2000 §4).
double normal_tail(double r, ExtraBlocks& blocks) {
  for (;;) {
    const PhiloxBlock block = blocks.next();
    const double x = -std::log(1.0 - unit_interval(block[0], block[1])) / r;  // log of (0, 1]
    const double y = -std::log(1.0 - unit_interval(block[2], block[3]));
    if (2.0 * y > x * x) return r + x;
  }
}

}  // namespace

PhiloxBlock philox4x32_10(PhiloxBlock counter, std::array<std::uint32_t, 2> key) {
  for (int round = 0; round < 10; ++round) {
    std::uint32_t hi0, lo0, hi1, lo1;
    mulhilo(kMultiplier0, counter[0], hi0, lo0);
    mulhilo(kMultiplier1, counter[2], hi1, lo1);
    counter = {hi1 ^ counter[1] ^ key[0], lo1, hi0 ^ counter[3] ^ key[1], lo0};
    key[0] += kWeyl0;
    key[1] += kWeyl1;
  }
  return counter;
}

PhiloxBlock random_block(const RandomKey& key) {
  return philox4x32_10(counter_of(key), philox_key(key.seed));
}

PhiloxBlock normal_extra_block(const RandomKey& key, std::uint32_t index) {
  PhiloxBlock counter = counter_of(key);
  counter[3] |= kExtraBlockFlag;
  return philox4x32_10(counter, philox_key(key.seed ^ (index * kExtraKeyStep)));
}

namespace {

constexpr std::size_t kLanes = 64;  // pulses per pass over the lanes

// Philox4x32-10 on each lane of four word arrays, in place (philox4x32_10's rounds, the lanes
// independent): GCC turns the 32 × 32 → 64-bit products into SSE2 vector multiplies.
void philox_lanes(std::size_t n, std::uint32_t* __restrict w0, std::uint32_t* __restrict w1,
                  std::uint32_t* __restrict w2, std::uint32_t* __restrict w3, std::uint32_t key0,
                  std::uint32_t key1) {
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t c0 = w0[i], c1 = w1[i], c2 = w2[i], c3 = w3[i];
    std::uint32_t k0 = key0, k1 = key1;
    for (int round = 0; round < 10; ++round) {
      const std::uint64_t product0 = static_cast<std::uint64_t>(kMultiplier0) * c0;
      const std::uint64_t product1 = static_cast<std::uint64_t>(kMultiplier1) * c2;
      const auto hi0 = static_cast<std::uint32_t>(product0 >> 32);
      const auto hi1 = static_cast<std::uint32_t>(product1 >> 32);
      c0 = hi1 ^ c1 ^ k0;
      c1 = static_cast<std::uint32_t>(product1);
      c2 = hi0 ^ c3 ^ k1;
      c3 = static_cast<std::uint32_t>(product0);
      k0 += kWeyl0;
      k1 += kWeyl1;
    }
    w0[i] = c0;
    w1[i] = c1;
    w2[i] = c2;
    w3[i] = c3;
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define OWSIM_PHILOX_AVX2 1
// The high and low words of m · c on each of 8 lanes: vpmuludq multiplies the even lanes, and the
// odd ones shifted down; the halves are blended back into lane order.
[[gnu::target("avx2")]] inline void mulhilo_8(__m256i m, __m256i c, __m256i& hi, __m256i& lo) {
  const __m256i even = _mm256_mul_epu32(m, c);
  const __m256i odd = _mm256_mul_epu32(m, _mm256_srli_epi64(c, 32));
  hi = _mm256_blend_epi32(_mm256_srli_epi64(even, 32), odd, 0xAA);
  lo = _mm256_blend_epi32(even, _mm256_slli_epi64(odd, 32), 0xAA);
}

// philox_lanes over 8 lanes a step with AVX2's 32 × 32 → 64-bit products written out (GCC's own
// vectorisation of the loop above spends most of its time shuffling); the last n % 8 lanes by
// the loop above. The same bits.
[[gnu::target("avx2")]] void philox_lanes_avx2(std::size_t n, std::uint32_t* w0, std::uint32_t* w1,
                                               std::uint32_t* w2, std::uint32_t* w3,
                                               std::uint32_t key0, std::uint32_t key1) {
  const __m256i m0 = _mm256_set1_epi32(static_cast<int>(kMultiplier0));
  const __m256i m1 = _mm256_set1_epi32(static_cast<int>(kMultiplier1));
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    __m256i c0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w0 + i));
    __m256i c1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w1 + i));
    __m256i c2 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w2 + i));
    __m256i c3 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w3 + i));
    std::uint32_t k0 = key0, k1 = key1;
    for (int round = 0; round < 10; ++round) {
      __m256i hi0, lo0, hi1, lo1;
      mulhilo_8(m0, c0, hi0, lo0);
      mulhilo_8(m1, c2, hi1, lo1);
      c0 = _mm256_xor_si256(_mm256_xor_si256(hi1, c1), _mm256_set1_epi32(static_cast<int>(k0)));
      c1 = lo1;
      c2 = _mm256_xor_si256(_mm256_xor_si256(hi0, c3), _mm256_set1_epi32(static_cast<int>(k1)));
      c3 = lo0;
      k0 += kWeyl0;
      k1 += kWeyl1;
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w0 + i), c0);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w1 + i), c1);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w2 + i), c2);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w3 + i), c3);
  }
  philox_lanes(n - i, w0 + i, w1 + i, w2 + i, w3 + i, key0, key1);
}

// GCC 12's AVX-512 shift intrinsics pass an undefined vector through and warn of it where they
// are inlined (GCC bug 105593, fixed in 13): the warning is about the header, not this code.
#if !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
// mulhilo_8 on 16 lanes (AVX-512F).
[[gnu::target("avx512f")]] inline void mulhilo_16(__m512i m, __m512i c, __m512i& hi, __m512i& lo) {
  const __m512i even = _mm512_mul_epu32(m, c);
  const __m512i odd = _mm512_mul_epu32(m, _mm512_srli_epi64(c, 32));
  hi = _mm512_mask_blend_epi32(0xAAAA, _mm512_srli_epi64(even, 32), odd);
  lo = _mm512_mask_blend_epi32(0xAAAA, even, _mm512_slli_epi64(odd, 32));
}

// philox_lanes_avx2 over 16 lanes a step; the last n % 16 lanes by it. The same bits.
[[gnu::target("avx512f")]] void philox_lanes_avx512(std::size_t n, std::uint32_t* w0,
                                                    std::uint32_t* w1, std::uint32_t* w2,
                                                    std::uint32_t* w3, std::uint32_t key0,
                                                    std::uint32_t key1) {
  const __m512i m0 = _mm512_set1_epi32(static_cast<int>(kMultiplier0));
  const __m512i m1 = _mm512_set1_epi32(static_cast<int>(kMultiplier1));
  std::size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    __m512i c0 = _mm512_loadu_si512(w0 + i);
    __m512i c1 = _mm512_loadu_si512(w1 + i);
    __m512i c2 = _mm512_loadu_si512(w2 + i);
    __m512i c3 = _mm512_loadu_si512(w3 + i);
    std::uint32_t k0 = key0, k1 = key1;
    for (int round = 0; round < 10; ++round) {
      __m512i hi0, lo0, hi1, lo1;
      mulhilo_16(m0, c0, hi0, lo0);
      mulhilo_16(m1, c2, hi1, lo1);
      c0 = _mm512_xor_si512(_mm512_xor_si512(hi1, c1), _mm512_set1_epi32(static_cast<int>(k0)));
      c1 = lo1;
      c2 = _mm512_xor_si512(_mm512_xor_si512(hi0, c3), _mm512_set1_epi32(static_cast<int>(k1)));
      c3 = lo0;
      k0 += kWeyl0;
      k1 += kWeyl1;
    }
    _mm512_storeu_si512(w0 + i, c0);
    _mm512_storeu_si512(w1 + i, c1);
    _mm512_storeu_si512(w2 + i, c2);
    _mm512_storeu_si512(w3 + i, c3);
  }
  philox_lanes_avx2(n - i, w0 + i, w1 + i, w2 + i, w3 + i, key0, key1);
}
#if !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif

// philox_lanes on the CPU's widest lanes.
void philox_words(std::size_t n, std::uint32_t* w0, std::uint32_t* w1, std::uint32_t* w2,
                  std::uint32_t* w3, std::uint32_t key0, std::uint32_t key1) {
#ifdef OWSIM_PHILOX_AVX2
  static const bool avx512 = __builtin_cpu_supports("avx512f") != 0;
  if (avx512) {
    philox_lanes_avx512(n, w0, w1, w2, w3, key0, key1);
    return;
  }
  static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
  if (avx2) {
    philox_lanes_avx2(n, w0, w1, w2, w3, key0, key1);
    return;
  }
#endif
  philox_lanes(n, w0, w1, w2, w3, key0, key1);
}

// random_block of the keys (seed, frame, pulse_at(i), purpose) for i < out.size(), over the lanes.
template <typename PulseAt>
void blocks_of(std::uint64_t seed, std::int64_t frame, const PulseAt& pulse_at,
               RandomPurpose purpose, std::span<PhiloxBlock> out) {
  const std::array<std::uint32_t, 2> key = philox_key(seed);
  alignas(64) std::uint32_t words[4][kLanes];
  for (std::size_t done = 0; done < out.size(); done += kLanes) {
    const std::size_t n = std::min(kLanes, out.size() - done);
    for (std::size_t i = 0; i < n; ++i) {
      const PhiloxBlock counter = counter_of({seed, frame, pulse_at(done + i), purpose});
      for (std::size_t w = 0; w < 4; ++w) words[w][i] = counter[w];
    }
    philox_words(n, words[0], words[1], words[2], words[3], key[0], key[1]);
    for (std::size_t i = 0; i < n; ++i) {
      out[done + i] = {words[0][i], words[1][i], words[2][i], words[3][i]};
    }
  }
}

}  // namespace

void random_blocks(std::uint64_t seed, std::int64_t frame, std::int64_t first_pulse,
                   RandomPurpose purpose, std::span<PhiloxBlock> out) {
  blocks_of(
      seed, frame, [&](std::size_t i) { return first_pulse + static_cast<std::int64_t>(i); },
      purpose, out);
}

void random_blocks(std::uint64_t seed, std::int64_t frame, std::span<const std::int64_t> pulses,
                   RandomPurpose purpose, std::span<PhiloxBlock> out) {
  if (pulses.size() != out.size()) throw Error("random blocks: pulses and blocks differ in count");
  blocks_of(
      seed, frame, [&](std::size_t i) { return pulses[i]; }, purpose, out);
}

double uniform01(const RandomKey& key) {
  const PhiloxBlock block = random_block(key);
  return unit_interval(block[0], block[1]);
}

double uniform_pm1(const RandomKey& key) { return 2.0 * uniform01(key) - 1.0; }

double standard_normal(const RandomKey& key) { return standard_normal(key, random_block(key)); }

void first_block_normals(std::span<const PhiloxBlock> blocks, std::span<double> out) {
  const Ziggurat& z = ziggurat();
  const std::size_t n = std::min(blocks.size(), out.size());
  for (std::size_t i = 0; i < n; ++i) {
    // standard_normal's first test, on the same bits.
    const std::uint64_t bits = join(blocks[i][0], blocks[i][1]);
    const auto strip = static_cast<std::size_t>(bits & 0xFFu);
    const std::uint64_t sign = (bits & 0x100u) << 55;
    const double x = unit_interval(bits) * z.edge[strip];
    out[i] = x < z.edge[strip + 1] ? signed_by(x, sign) : std::numeric_limits<double>::quiet_NaN();
  }
}

double standard_normal(const RandomKey& key, const PhiloxBlock& first) {
  const Ziggurat& z = ziggurat();
  ExtraBlocks extra(key);
  for (PhiloxBlock block = first;; block = extra.next()) {
    // Words 0-1: the top 53 bits are the uniform, bits 0-7 the strip, bit 8 the sign.
    const std::uint64_t bits = join(block[0], block[1]);
    const auto strip = static_cast<std::size_t>(bits & 0xFFu);
    const std::uint64_t sign = (bits & 0x100u) << 55;
    const double x = unit_interval(bits) * z.edge[strip];
    if (x < z.edge[strip + 1]) return signed_by(x, sign);
    if (strip == 0) return signed_by(normal_tail(z.r, extra), sign);
    // The wedge between the strip's inner rectangle and the curve.
    const double y = z.height[strip] +
                     unit_interval(block[2], block[3]) * (z.height[strip + 1] - z.height[strip]);
    if (y < half_normal_density(x)) return signed_by(x, sign);
  }
}

}  // namespace owsim
