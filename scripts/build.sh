#!/usr/bin/env bash
# Configures and builds owsim (Release) into build/ — used by the quick-start scripts.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
