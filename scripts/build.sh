#!/usr/bin/env bash
# Configures and builds owsim (Release) into build/ — used by the quick-start scripts:
#   build.sh [--target TARGET]... [CMAKE_OPTION]...
# every target unless some are named; the options go to the configuration.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_BUILD_DIR:-$root/build}"
targets=() options=()
while [ $# -gt 0 ]; do
  case $1 in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) options+=("$1"); shift ;;
  esac
done
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${options[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)" "${targets[@]}"
