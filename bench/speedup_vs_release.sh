#!/usr/bin/env bash
# Whole-process speed of this build's `owsim run` against a release built from history (issue 46):
# the words only (`--outputs d64`), the default receiver, every core, on the corridor, the flat-
# ground wire scene of the HELIOS++ comparison and the real corridor (DEM, mesh, GIS lines).
# Runs alternate (release first on odd rounds, this build first on even ones) so drift on a
# noisy machine falls on both alike; the figure is the median of the paired per-round ratios.
#
#   bench/speedup_vs_release.sh [BUILD_DIR] [--rounds N] [--ref COMMIT] [--threads N]
#
# BUILD_DIR (default build/) holds this tree's owsim. The release (default ad229ca, 0.1.0) is
# built once into BUILD_DIR/bench-release-COMMIT from `git archive` of that commit, target owsim
# only, and reused afterwards.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
build=""
rounds=9
ref=ad229ca
threads=""
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --ref) ref=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    -*) echo "speedup_vs_release: unknown option $1" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
build=$(cd "${build:-$repo/build}" && pwd)
current="$build/owsim"
[ -x "$current" ] || { echo "speedup_vs_release: no owsim in $build (build it first)" >&2; exit 2; }

# The release, from history.
commit=$(git -C "$repo" rev-parse --short=7 "$ref^{commit}")
release_dir="$build/bench-release-$commit"
release="$release_dir/build/owsim"
if [ ! -x "$release" ]; then
  echo "speedup_vs_release: building owsim at $commit in $release_dir"
  rm -rf "$release_dir/src"
  mkdir -p "$release_dir/src"
  git -C "$repo" archive "$commit" | tar -x -C "$release_dir/src"
  # Its build bundles the report page's script: the same pinned npm packages as this tree's.
  ln -s "$repo/web/node_modules" "$release_dir/src/web/node_modules"
  launcher=()
  if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
  cmake -S "$release_dir/src" -B "$release_dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    "${launcher[@]}" >"$release_dir/configure.log"
  cmake --build "$release_dir/build" --target owsim >"$release_dir/build.log"
fi

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
thread_args=()
if [ -n "$threads" ]; then thread_args=(--threads "$threads"); fi

# Seconds of wall time of one whole `owsim run` process.
run_once() {
  local binary=$1 scenario=$2
  rm -rf "$scratch/out"
  local start end
  start=$(date +%s%N)
  "$binary" run "$scenario" --out "$scratch/out" --outputs d64 --quiet "${thread_args[@]}"
  end=$(date +%s%N)
  echo $(( (end - start) / 1000 ))
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "owsim run --outputs d64, ${threads:-every} thread(s): this build ($current) against $commit;"
echo "median of $rounds paired alternating rounds (release time / this build's time per round)"
for scenario in examples/corridor.yaml bench/scenes/flat_wires.yaml examples/real_corridor.yaml; do
  ratios=()
  old_times=()
  new_times=()
  for ((round = 1; round <= rounds; ++round)); do
    if ((round % 2)); then
      old=$(run_once "$release" "$repo/$scenario")
      new=$(run_once "$current" "$repo/$scenario")
    else
      new=$(run_once "$current" "$repo/$scenario")
      old=$(run_once "$release" "$repo/$scenario")
    fi
    old_times+=("$old")
    new_times+=("$new")
    ratios+=("$(awk -v a="$old" -v b="$new" 'BEGIN {printf "%.4f", a / b}')")
  done
  ratio=$(printf '%s\n' "${ratios[@]}" | median)
  old_median=$(printf '%s\n' "${old_times[@]}" | median)
  new_median=$(printf '%s\n' "${new_times[@]}" | median)
  printf '  %-30s %s %7.3f s   this build %7.3f s   speed-up %.2fx\n' "$scenario" "$commit" \
    "$(awk -v t="$old_median" 'BEGIN {print t / 1e6}')" \
    "$(awk -v t="$new_median" 'BEGIN {print t / 1e6}')" "$ratio"
done
