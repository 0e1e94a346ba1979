#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang -fsanitize=fuzzer,address,undefined) into
# build-fuzz/ and runs each for a bounded time from its seed corpus (fuzz/corpus/<target>/),
# printing the executions each ran. Exits non-zero when a target crashes; the crashing input is
# left in build-fuzz/findings/<target>/ (make it a regression test in the reader's test file).
# Line tables only, as scripts/sanitize.sh: crash reports name file and line.
# OWSIM_FUZZ_SECONDS sets the time per target (default 10: CI runs every target on each landing,
# ~2,000–80,000 executions each; longer hunts set more).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${OWSIM_FUZZ_SECONDS:-10}"
flags="-O1 -gline-tables-only -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined"
flags+=" -fno-sanitize-recover=undefined"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG= \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="$flags" \
  -DOWSIM_BUILD_TESTS=OFF -DOWSIM_BUILD_BENCH=OFF -DOWSIM_BUILD_FUZZ=ON >/dev/null
targets=()
for source in "$root"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$source" .cpp)"); done
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"

# As scripts/sanitize.sh: no scan of dlopen'ed libraries' dynamic TLS (LeakSanitizer's tracer
# crashes on it now and then with Debian 12's glibc).
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:intercept_tls_get_addr=0}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$root/fuzz/lsan_suppressions.txt}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
# The targets write each input to a file under the temp folder (fuzz/fuzz_input_file.hpp) and
# libFuzzer ends them with exit(), so the last file of each stays: a scratch folder of this run's.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export TMPDIR="$scratch"
failed=()
for target in "${targets[@]}"; do
  name=${target#fuzz_}
  corpus="$build/corpus/$name"        # grows as the fuzzer runs; the seeds stay untouched
  findings="$build/findings/$name"
  mkdir -p "$corpus" "$findings"
  log="$build/$target.log"
  status=0
  "$build/fuzz/$target" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=8192 \
    -artifact_prefix="$findings/" "$corpus" "$root/fuzz/corpus/$name" >"$log" 2>&1 || status=$?
  runs=$(grep -oE 'Done [0-9]+ runs' "$log" | grep -oE '[0-9]+' || true)
  if [ "$status" -ne 0 ]; then
    echo "fuzz: $target FAILED (exit $status) — see $log and $findings/"
    grep -E 'ERROR|runtime error|==ABORTING|terminate' "$log" | head -5 || true
    failed+=("$target")
  else
    echo "fuzz: $target ${runs:-?} executions in ${seconds} s, no crash"
  fi
done
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) crashed: ${failed[*]}"
  exit 1
fi
