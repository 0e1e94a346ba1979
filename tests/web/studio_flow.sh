#!/usr/bin/env bash
# `owsim studio` end to end (tests/web/studio_flow.mjs): the real recorded flight copied into a
# fresh folder, the studio started on it, the user's job done in headless Chromium; the bundled
# real_corridor's DEM shaded and contoured on the map; then `owsim run` of the saved scenario must
# write the same bytes as the studio's Fly did. Screenshots in BUILD/web-studio-screens (CI
# artifacts); the flights in BUILD/web-studio (~650 MB) only when a check failed.
#   tests/web/studio_flow.sh BUILD_DIR SHARED_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
shared=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
owsim="$build/owsim"
log="$shared/data/real/WingFlight1.log"
if [ ! -f "$log" ]; then
  echo "studio_flow: $log not found: skipped"
  exit 0
fi
work="$build/web-studio"
shots="$build/web-studio-screens"
rm -rf "$work" "$shots"
mkdir -p "$work" "$shots"
cp "$log" "$work/"

# Starts `owsim studio INPUT` in the background (its pid in $studio) and waits for its address,
# the first line it prints, into $address.
start_studio() {
  "$owsim" studio "$1" --no-browser > "$2.out" 2> "$2.err" &
  studio=$!
  trap 'kill $studio 2>/dev/null || true' EXIT
  for _ in $(seq 100); do
    [ -s "$2.out" ] && break
    sleep 0.1
  done
  address=$(head -n 1 "$2.out")
}

start_studio "$work/WingFlight1.log" "$work/studio"
case "$address" in
  http://127.0.0.1:*/\?token=*) ;;
  *) echo "studio_flow: the studio printed '$address' first"; cat "$work/studio.err"; exit 1 ;;
esac

node "$root/tests/web/studio_flow.mjs" "$address" "$shots"

# Ctrl-C stops it cleanly.
kill -INT $studio
wait $studio
trap - EXIT

# A scenario with a DEM (the bundled real_corridor, copied with its data): hillshade and contours.
mkdir -p "$work/dem"
cp "$root/examples/real_corridor.yaml" "$work/dem/"
cp -r "$root/examples/data" "$work/dem/"
start_studio "$work/dem/real_corridor.yaml" "$work/dem"
node "$root/tests/web/studio_flow.mjs" "$address" "$shots" --terrain
kill -TERM $studio
wait $studio
trap - EXIT

# The saved scenario flown by owsim run: the same bytes as the studio's run.
"$owsim" run "$work/WingFlight1.yaml" --out "$work/cli" --quiet
for file in flight.d64 points.csv points.las truth.csv trajectory.csv; do
  cmp "$work/out/WingFlight1/$file" "$work/cli/$file"
done
rm -rf "$work"
echo "studio_flow: owsim run of the saved scenario wrote the studio's bytes"
