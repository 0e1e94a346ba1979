#pragma once
// Array loops that GCC compiles for AVX2 as well as the x86-64 baseline (SSE2); the CPU's best is
// chosen when the program loads, and the loops run on twice the lanes. "avx2" does not enable
// FMA, so both versions round every operation alike: the same bits on every machine.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define OWSIM_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define OWSIM_AVX2_CLONE
#endif
