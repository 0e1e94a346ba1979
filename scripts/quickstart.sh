#!/usr/bin/env bash
# Quick start, first command: install dependencies, build, and simulate the bundled example
# (examples/single_span.yaml: a 20 mm conductor between two poles, approached head-on) into
# out/single_span/, then check the recording it wrote.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_BUILD_DIR:-$root/build}"
"$root/scripts/setup.sh"
OWSIM_BUILD_DIR="$build" "$root/scripts/build.sh"
cd "$root"
"$build/owsim" run examples/single_span.yaml --out out/single_span
"$build/owsim" info out/single_span/flight.d64
echo
echo "outputs in $root/out/single_span:"
ls -l out/single_span
