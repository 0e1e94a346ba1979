#!/usr/bin/env bash
# Builds the tests with AddressSanitizer + UndefinedBehaviorSanitizer (-O1, any UB is fatal) into
# build-asan/ and runs them: the C ABI's tests through the instrumented libowsim_c.so, the Python
# module's in /usr/bin/python3 with the sanitizer runtimes preloaded (tests/CMakeLists.txt).
# Embree, TBB and the other system libraries are not instrumented.
# Line tables only (-g1; Debug's own -g is dropped): the sanitizers' stack traces still name file
# and line, and the build takes ~23 % less time (4 heavy units: 31-33 s with -g, 24-25 s with -g1).
# The tests and the owsim command's own sources at -Og (OWSIM_DRIVER_COMPILE_OPTIONS): they are
# ~1,500 of the build's ~2,300 compile-seconds at -O1 and compile in 25-40 % less at -Og
# (test_run_outputs 22.8 s -> 16.9 s, test_evidence_cli 25.7 s -> 15.8 s). -O0 saves a little more
# but the tests' own brute-force loops then run 10-20x slower (RaySegment's 9 s -> 197 s). The
# libraries, where the suite spends its time, stay at -O1.
# The modules are shared libraries here (OWSIM_MODULE_LIBRARY_TYPE): linked statically, each of the
# ~120 instrumented test programs (one per test file then; 11 since issue 73) held its own ~60 MB
# copy of them, 7.4 GB of build tree in all.
# OWSIM_SANITIZE_EXCLUDE is a ctest regex of tests left out (default: none).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_SANITIZE_BUILD_DIR:-$root/build-asan}"
flags="-O1 -g1 -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined"
link="-fsanitize=address,undefined"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG= \
  -DCMAKE_CXX_FLAGS_DEBUG= -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="$link" -DCMAKE_SHARED_LINKER_FLAGS="$link" \
  -DCMAKE_MODULE_LINKER_FLAGS="$link" \
  -DOWSIM_DRIVER_COMPILE_OPTIONS=-Og -DOWSIM_MODULE_LIBRARY_TYPE=SHARED -DOWSIM_REQUIRE_ALL=ON \
  -DOWSIM_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)"
# Leak checking is on: the whole suite runs leak-free, TBB and Embree included. The dynamic TLS of
# dlopen'ed libraries (GDAL and PROJ behind libowsim_gdal.so) is not scanned: LeakSanitizer's
# tracer crashes on it now and then with Debian 12's glibc ("Tracer caught signal 11", seen in CI;
# google/sanitizers#1322), while static TLS, stacks and globals still are.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
exclude=()
if [ -n "${OWSIM_SANITIZE_EXCLUDE:-}" ]; then exclude=(-E "$OWSIM_SANITIZE_EXCLUDE"); fi
ctest --test-dir "$build" -j "$(nproc)" --output-on-failure "${exclude[@]}"
