#!/usr/bin/env bash
# Build time, measured (issue 73): a clean build of TARGET in an empty folder on this machine, with
# the quick start's own build script (scripts/build.sh: Release, Ninja, every core), then its wall
# time and the slowest steps from ninja's log — compile units and links by their own seconds, and
# the compiler-seconds in all. Or, with --log, the same table from a build folder that exists.
#   bench/build_time.sh [TARGET] [--top N] [--keep] [-- CMAKE_OPTION...]   default owsim_cli, 15
#   bench/build_time.sh --log BUILD_DIR [--top N]
# The build folder is a temporary one (removed unless --keep); ccache is not used (CMAKE_*_LAUNCHER
# are left unset), so the figure is a fresh clone's.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
target=owsim_cli top=15 keep=0 log_dir="" options=()
while [ $# -gt 0 ]; do
  case $1 in
    --top) top=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    --log) log_dir=$2; shift 2 ;;
    --) shift; options=("$@"); break ;;
    *) target=$1; shift ;;
  esac
done

# The slowest steps of a ninja log (v5: start ms, end ms, mtime, output, hash), each output's last
# run, and the sum of all steps' seconds.
report() {
  awk -v top="$top" '
    /^#/ { next }
    { seconds[$4] = ($2 - $1) / 1000.0 }
    END {
      total = 0; n = 0
      for (out in seconds) { total += seconds[out]; n++ }
      printf "%d steps, %.0f s of step time in all (compiler and linker seconds)\n", n, total
      cmd = "sort -rn | head -n " top
      for (out in seconds) printf "%8.1f s  %s\n", seconds[out], out | cmd
      close(cmd)
    }' "$1/.ninja_log"
}

if [ -n "$log_dir" ]; then
  report "$log_dir"
  exit 0
fi
build=$(mktemp -d)
[ "$keep" -eq 1 ] || trap 'rm -rf "$build"' EXIT
start=$(date +%s.%N)
OWSIM_BUILD_DIR="$build" "$root/scripts/build.sh" --target "$target" "${options[@]}" >/dev/null
end=$(date +%s.%N)
printf '%s: clean build in %.0f s wall on %s cores (%s)\n' "$target" "$(echo "$end - $start" | bc)" \
  "$(nproc)" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
report "$build"
[ "$keep" -eq 0 ] || echo "build folder kept: $build"
