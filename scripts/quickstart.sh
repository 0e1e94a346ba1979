#!/usr/bin/env bash
# Quick start, first command: install what building and running the `owsim` command needs, build
# that command (with the quick-look image module the example's images use), and simulate the
# bundled example (examples/single_span.yaml: a 20 mm conductor between two poles, approached
# head-on) into out/single_span/, then check the recording it wrote. The tests, the benchmarks
# and the other optional modules (DEM terrain, model files, MPI, Python) come with
# scripts/test.sh, or one by one with scripts/setup.sh PART.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_BUILD_DIR:-$root/build}"
"$root/scripts/setup.sh" core png
OWSIM_BUILD_DIR="$build" "$root/scripts/build.sh" --target owsim_cli
cd "$root"
"$build/owsim" run examples/single_span.yaml --out out/single_span
"$build/owsim" info out/single_span/flight.d64
echo
echo "outputs in $root/out/single_span:"
ls -l out/single_span
