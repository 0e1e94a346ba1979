#include "geometry/keyed_random.hpp"

#include <cmath>
#include <numbers>

namespace owsim {
namespace {

constexpr std::uint32_t kMultiplier0 = 0xD2511F53u;
constexpr std::uint32_t kMultiplier1 = 0xCD9E8D57u;
constexpr std::uint32_t kWeyl0 = 0x9E3779B9u;  // golden ratio
constexpr std::uint32_t kWeyl1 = 0xBB67AE85u;  // sqrt(3) - 1

void mulhilo(std::uint32_t a, std::uint32_t b, std::uint32_t& hi, std::uint32_t& lo) {
  const std::uint64_t product = static_cast<std::uint64_t>(a) * b;
  hi = static_cast<std::uint32_t>(product >> 32);
  lo = static_cast<std::uint32_t>(product);
}

// 53 random bits from two 32-bit words, as a double in [0, 1).
double unit_interval(std::uint32_t high, std::uint32_t low) {
  const std::uint64_t bits = ((static_cast<std::uint64_t>(high) << 32) | low) >> 11;
  return static_cast<double>(bits) * 0x1.0p-53;
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
  const auto frame = static_cast<std::uint64_t>(key.frame);
  const PhiloxBlock counter = {static_cast<std::uint32_t>(frame), static_cast<std::uint32_t>(frame >> 32),
                               static_cast<std::uint32_t>(key.pulse),
                               static_cast<std::uint32_t>(key.purpose) |
                                   (static_cast<std::uint32_t>(static_cast<std::uint64_t>(key.pulse) >> 32) << 8)};
  return philox4x32_10(counter, {static_cast<std::uint32_t>(key.seed),
                                 static_cast<std::uint32_t>(key.seed >> 32)});
}

double uniform01(const RandomKey& key) {
  const PhiloxBlock block = random_block(key);
  return unit_interval(block[0], block[1]);
}

double uniform_pm1(const RandomKey& key) { return 2.0 * uniform01(key) - 1.0; }

double standard_normal(const RandomKey& key) {
  const PhiloxBlock block = random_block(key);
  const double u1 = 1.0 - unit_interval(block[0], block[1]);  // (0, 1]: log is finite
  const double u2 = unit_interval(block[2], block[3]);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace owsim
