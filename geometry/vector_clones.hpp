#pragma once
// Array loops that GCC compiles for AVX-512 (x86-64-v4) and AVX2 as well as the x86-64 baseline
// (SSE2); the CPU's best is chosen when the program loads, and the loops run on four or two times
// the lanes. The project is compiled with -ffp-contract=off (CMakeLists.txt): x86-64-v4 has FMA,
// but no multiply and add is fused, so every version rounds every operation alike — the same bits
// on every machine.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define OWSIM_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define OWSIM_VECTOR_CLONES
#endif
