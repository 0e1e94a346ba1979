#pragma once
// Denormal floats flushed to zero while a worker traces (DESIGN.md "Performance model"; Embree's
// advice for its traversal kernels): on x86, sets the MXCSR flush-to-zero and denormals-are-zero
// bits for the guard's lifetime and restores the caller's bits after, so a program that embeds
// owsim keeps its own floating-point environment. Every task of a frame takes one, whichever
// thread runs it, so results do not depend on the thread. Elsewhere it does nothing.
#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#define OWSIM_HAS_MXCSR 1
#endif

namespace owsim {

class FlushDenormalsToZero {
 public:
#ifdef OWSIM_HAS_MXCSR
  static constexpr unsigned kBits = 0x8040;  // FTZ (bit 15) | DAZ (bit 6)
  FlushDenormalsToZero() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kBits); }
  ~FlushDenormalsToZero() { _mm_setcsr(saved_); }
#else
  FlushDenormalsToZero() = default;
  ~FlushDenormalsToZero() = default;
#endif
  FlushDenormalsToZero(const FlushDenormalsToZero&) = delete;
  FlushDenormalsToZero& operator=(const FlushDenormalsToZero&) = delete;

 private:
#ifdef OWSIM_HAS_MXCSR
  unsigned saved_;
#endif
};

}  // namespace owsim
