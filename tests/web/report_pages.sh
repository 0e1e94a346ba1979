#!/usr/bin/env bash
# `owsim view` end to end in a real browser (tests/web/report_page.mjs): the report of a run of
# the corridor example, of a recording decoded without labels (as from real data: no summary, no
# trajectory, no classes), of a words-only run (no points), of a LAS-only run, and of a run thinned
# to a small budget; and the refusal of a folder that is no owsim output. Screenshots stay in
# BUILD/web-screens (CI artifacts); the runs in BUILD/web-report (~400 MB) only when a check failed.
#   tests/web/report_pages.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
owsim="$build/owsim"
out="$build/web-report"
shots="$build/web-screens"
rm -rf "$out" "$shots"
mkdir -p "$out" "$shots"
cd "$root"
page() { node "$root/tests/web/report_page.mjs" "$@"; }

# 1. A simulated run: summary, ground truth, frames with wire marks, map, 3D with the scene, and
#    the detection evidence of its wires, of the same flight at two thresholds (owsim roc over a
#    small sweep, written into the run's folder) and of the numpy example detector; the reference
#    detector's warnings (owsim detect) under the frame player and on the map.
"$owsim" run examples/corridor.yaml --out "$out/corridor" --frames 90 --quiet
"$owsim" pd "$out/corridor" --class wire --quiet
mkdir -p "$out/thresholds"
cp examples/corridor.yaml "$out/thresholds/"
printf '%s\n' 'base: corridor.yaml' 'count: 4' 'seed: 3' 'outputs: summary,truth' 'vary:' \
  '  sensor.threshold: {values: [0.003, 0.005]}' '  trajectory.duration_s: {values: [30]}' \
  '  seed: {member: true}' > "$out/thresholds/sweep.yaml"
"$owsim" sweep "$out/thresholds/sweep.yaml" --out "$out/thresholds/campaign" --quiet
"$owsim" roc "$out/thresholds/campaign" --range 400:800 --out "$out/corridor" --quiet
/usr/bin/python3 examples/detectors/elevated_returns.py "$out/corridor" "$out/corridor_detections.csv"
"$owsim" score "$out/corridor" --detections "$out/corridor_detections.csv" --quiet
"$owsim" detect "$out/corridor" --quiet
"$owsim" view "$out/corridor" --scenario examples/corridor.yaml --quiet
page "$out/corridor/report.html" "$shots/corridor" --expect-frames --expect-objects --expect-wires \
  --expect-evidence --expect-roc 2 --expect-warnings

# 2. Its words decoded without labels, viewed without the scenario: what real data gives.
"$owsim" decode "$out/corridor/flight.d64" --scenario examples/corridor.yaml --no-labels \
  --outputs csv --out "$out/decoded" --quiet
"$owsim" view "$out/decoded" --quiet
page "$out/decoded/report.html" "$shots/decoded" --expect-frames \
  --expect-note "No summary.json in this folder"

# 3. Words only: no points to show, said in the page.
"$owsim" run examples/single_span.yaml --out "$out/words_only" --outputs d64,summary,trajectory --quiet
"$owsim" view "$out/words_only" --scenario examples/single_span.yaml --quiet
page "$out/words_only/report.html" "$shots/words_only" --expect-objects --expect-empty \
  --expect-note "No point file in this folder"

# 4. LAS alone: placed through the origin trajectory.csv implies; no frame player (LAS has no
#    frame, line or fiber), said in the page.
"$owsim" run examples/corridor.yaml --out "$out/las_only" --frames 30 --outputs las,summary,trajectory --quiet
"$owsim" view "$out/las_only" --quiet
page "$out/las_only/report.html" "$shots/las_only" --expect-objects \
  --expect-note "The frame player needs points.csv"

# 5. A budget smaller than the flight: thinned, and the page says how.
"$owsim" view "$out/corridor" --out "$out/thinned.html" --max-points 50000 --max-frames 7 --quiet
page "$out/thinned.html" "$shots/thinned" --expect-frames --expect-objects --expect-evidence \
  --expect-note "The 3D view shows 50,000 of"

# 5b. A receiver far noisier than the default: false returns (class noise) in the summary, the
#     legends and the frames.
sed -e 's/^  returns: first_second$/  returns: first_second\n  receiver: {noise: on, noise_at_1km: 0.0015}/' \
  -e 's/^name: single_span$/name: noisy_span/' examples/single_span.yaml > "$out/noisy_span.yaml"
grep -q "noise_at_1km" "$out/noisy_span.yaml" || { echo "FAIL: no receiver key in noisy_span.yaml" >&2; exit 1; }
"$owsim" run "$out/noisy_span.yaml" --out "$out/noisy" --frames 6 --quiet
"$owsim" view "$out/noisy" --quiet
page "$out/noisy/report.html" "$shots/noisy" --expect-frames --expect-objects --expect-noise

# 6. Not an owsim folder: one line, non-zero, nothing written.
mkdir -p "$out/not_owsim"
echo "hello" > "$out/not_owsim/notes.txt"
if "$owsim" view "$out/not_owsim" 2> "$out/not_owsim.err"; then
  echo "FAIL: owsim view accepted a folder that is no owsim output" >&2
  exit 1
fi
if [ "$(wc -l < "$out/not_owsim.err")" -ne 1 ] || ! grep -q "not an owsim output folder" "$out/not_owsim.err" ||
   [ -e "$out/not_owsim/report.html" ]; then
  echo "FAIL: the refusal should be one line and leave no page:" >&2
  cat "$out/not_owsim.err" >&2
  exit 1
fi
rm -rf "$out"
echo "report pages: all checks passed (screenshots in $shots)"
