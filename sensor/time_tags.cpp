// milows_time_tags (sensor/scan_pattern.hpp): the time tags of a block of pulses over arrays. This
// file is compiled with -fno-trapping-math (CMakeLists.txt) so GCC vectorises the floors.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "geometry/error.hpp"
#include "geometry/vector_clones.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

// time_tag's common case over a block of times: the floored tick count as time_tag forms it
// (std::floor is round_down: both floor, both keep −0), wrapped into [0, 65536) in double — the
// quotient by a power of two, its floor and the product are exact, and so is the difference, an
// integer below 65536 — which is the int64 mask's value; `common` says |ticks| < 2⁶² held.
constexpr std::size_t kTagBlock = 256;
OWSIM_VECTOR_CLONES void wrapped_milows_ticks(const double* times_s, std::size_t n, double* wrapped,
                                              std::uint8_t* common) {
  constexpr double kTicksPerS = 1.0 / kMilowsTimeTagTickS;
  constexpr double kModulus = kMilowsTimeTagModulus;
  for (std::size_t i = 0; i < n; ++i) {
    const double ticks = times_s[i] * kTicksPerS;
    const double whole = std::floor(ticks + std::abs(ticks) * 1e-14);
    wrapped[i] = whole - kModulus * std::floor(whole * (1.0 / kModulus));
    common[i] = std::abs(whole) < 0x1p62 ? 1 : 0;
  }
}

}  // namespace

void milows_time_tags(std::span<const double> times_s, std::span<std::uint16_t> tags) {
  if (tags.size() != times_s.size()) throw Error("time tags: times and tags differ in count");
  double wrapped[kTagBlock];
  std::uint8_t common[kTagBlock];
  for (std::size_t first = 0; first < times_s.size(); first += kTagBlock) {
    const std::size_t n = std::min(kTagBlock, times_s.size() - first);
    wrapped_milows_ticks(times_s.data() + first, n, wrapped, common);
    for (std::size_t i = 0; i < n; ++i) {
      tags[first + i] = common[i] != 0 ? static_cast<std::uint16_t>(wrapped[i])
                                       : milows_time_tag(times_s[first + i]);
    }
  }
}

}  // namespace owsim
