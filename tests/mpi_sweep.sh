#!/bin/sh
# `owsim sweep` alone and under mpirun (issue 18): the same member folders (truth.csv included)
# and sweep.csv for one process and N = 2, 3; a resumed sweep reruns only what is missing; a bad sweep file is said in
# one line naming file, line and key; a bad member is said once before any member flies.
#   mpi_sweep.sh OWSIM SOURCE_DIR WORK_DIR
set -eu
owsim=$1
source=$2
work=$3
mpirun="${MPIRUN:-mpirun} --allow-run-as-root --oversubscribe --bind-to none"
same="/usr/bin/python3 $source/tests/same_outputs.py"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
cp "$source/examples/corridor.yaml" .  # a sweep file reads only its own folder tree
cat > sweep.yaml <<YAML
base: corridor.yaml
count: 7
seed: 11
outputs: d64,trajectory,summary,truth
vary:
  trajectory.duration_s: {values: [4, 9, 2, 6, 3, 8, 5]}   # members of different costs
  scene.spans[0].conductor.diameter_mm: {uniform: [5, 30]}
  trajectory.waypoints.speed_mps: {choice: [30, 35, 40]}
  sensor.mount.pitch_deg: {normal: [-4, 1]}
  seed: {member: true}
YAML

"$owsim" sweep sweep.yaml --out one --quiet
test "$(wc -l < one/sweep.csv)" -eq 8
head -1 one/sweep.csv | grep -q '^member,trajectory.duration_s,scene.spans\[0\].conductor.diameter_mm,'
for n in 2 3; do
  $mpirun -np $n "$owsim" sweep sweep.yaml --out mpi$n --quiet
  $same one mpi$n
done

# Resume: a member whose run did not finish is run again, the others are kept.
rm mpi3/2/summary.json mpi3/2/flight.d64
$mpirun -np 2 "$owsim" sweep sweep.yaml --out mpi3 --resume 2> resumed.log
grep -q '1 run, 6 complete before' resumed.log
$same one mpi3

# Another sweep file in the same folder is refused on --resume.
sed 's/seed: 11/seed: 12/' sweep.yaml > other.yaml
if "$owsim" sweep other.yaml --out one --resume 2> other.log; then
  echo "FAIL: resumed another sweep's folder"; exit 1
fi
grep -q "sweep_file" other.log

# A bad sweep file: one line with file, line and key.
sed 's/{normal: \[-4, 1\]}/{normal: [-4, -1]}/' sweep.yaml > bad.yaml
if $mpirun -np 2 "$owsim" sweep bad.yaml --out bad > bad.log 2>&1; then
  echo "FAIL: a bad sweep file ran"; exit 1
fi
lines=$(grep -c '^owsim:' bad.log)
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines error lines"; cat bad.log; exit 1; fi
grep '^owsim: bad.yaml:9: vary.sensor.mount.pitch_deg.normal:' bad.log
# A bad value in two members (issue 45): every member is checked before the first flies, the
# lowest bad one is said once whichever process found it, and nothing is written.
sed 's/{values: \[4, 9, 2, 6, 3, 8, 5\]}/{values: [4, x, 2, 6, x, 8, 5]}/' sweep.yaml > members.yaml
if $mpirun -np 2 "$owsim" sweep members.yaml --out members > members.log 2>&1; then
  echo "FAIL: a sweep with bad members ran"; exit 1
fi
lines=$(grep -c '^owsim:' members.log)
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines error lines"; cat members.log; exit 1; fi
grep '^owsim: members.yaml: member 1: ' members.log
if [ -e members ]; then echo "FAIL: a refused sweep wrote members/"; exit 1; fi
echo "mpi_sweep: ok"
