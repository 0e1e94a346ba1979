#!/usr/bin/env bash
# Quick start, second command: install every package (all optional modules, the tests' oracles,
# the browser, the fuzzing toolchain, packaging), build everything and run the whole test suite.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_BUILD_DIR:-$root/build}"
"$root/scripts/setup.sh"
OWSIM_BUILD_DIR="$build" "$root/scripts/build.sh" -DOWSIM_REQUIRE_ALL=ON -DOWSIM_BUILD_TESTS=ON \
  -DOWSIM_BUILD_BENCH=ON -DOWSIM_BUILD_PYTHON=ON
ctest --test-dir "$build" -j "$(nproc)" --output-on-failure
