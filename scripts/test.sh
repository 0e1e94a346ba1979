#!/usr/bin/env bash
# Quick start, second command: install dependencies, build, and run the whole test suite.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_BUILD_DIR:-$root/build}"
"$root/scripts/setup.sh"
OWSIM_BUILD_DIR="$build" "$root/scripts/build.sh"
ctest --test-dir "$build" -j "$(nproc)" --output-on-failure
