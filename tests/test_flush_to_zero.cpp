// Protects the denormal guard of the trace workers (engine/flush_to_zero.hpp): inside it a
// denormal result is flushed to zero and a denormal input reads as zero; after it the caller's
// floating-point environment is back, so an embedding program's arithmetic is untouched.
#include <gtest/gtest.h>

#include <limits>

#include "engine/flush_to_zero.hpp"

namespace owsim {
namespace {

#ifdef OWSIM_HAS_MXCSR
TEST(FlushDenormalsToZero, FlushesInsideAndRestoresTheCallersBits) {
  volatile double smallest_normal = std::numeric_limits<double>::min();  // 2.2e-308
  volatile double denormal = std::numeric_limits<double>::denorm_min();
  // The control bits (modes and masks); bits 0–5 are sticky exception flags, not the environment.
  constexpr unsigned kControl = ~0x3Fu;
  const unsigned before = _mm_getcsr() & kControl;
  EXPECT_GT(smallest_normal / 4.0, 0.0);  // gradual underflow outside the guard
  {
    const FlushDenormalsToZero guard;
    EXPECT_EQ(_mm_getcsr() & FlushDenormalsToZero::kBits, FlushDenormalsToZero::kBits);
    EXPECT_EQ(smallest_normal / 4.0, 0.0);  // FTZ: the denormal result becomes 0
    EXPECT_EQ(denormal * 1e300, 0.0);       // DAZ: the denormal input reads as 0
  }
  EXPECT_EQ(_mm_getcsr() & kControl, before);
  EXPECT_GT(smallest_normal / 4.0, 0.0);
  EXPECT_GT(denormal * 1e300, 0.0);
}
#endif

}  // namespace
}  // namespace owsim
