#!/bin/sh
# `mpirun -np N owsim run` against one process (issue 18): every output byte-identical for
# N = 1, 2, 3 (MilOWS with every output, HELLAS words and detections; flight.mcap for N = 2), a
# job killed mid-flight resumed by another number of processes to the same bytes, and bad input
# said in one line.
#   mpi_run.sh OWSIM SOURCE_DIR WORK_DIR
set -eu
owsim=$1
source=$2
work=$3
mpirun="${MPIRUN:-mpirun} --allow-run-as-root --oversubscribe --bind-to none"
same="/usr/bin/python3 $source/tests/same_outputs.py"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
sed 's/model: milows/model: hellas/' "$source/examples/corridor.yaml" > hellas.yaml

# 50 frames with 8 a block: N = 3 runs two full rounds and a last one only process 0 has frames in.
"$owsim" run "$source/examples/corridor.yaml" --frames 50 --threads 1 --out ref --quiet
"$owsim" run hellas.yaml --frames 30 --threads 1 --outputs d64,summary,detections \
  --out ref_hellas --quiet
for n in 1 2 3; do
  $mpirun -np $n "$owsim" run "$source/examples/corridor.yaml" --frames 50 --threads 1 \
    --out mpi$n --quiet
  $same ref mpi$n
  [ $n -ne 3 ] || grep -q '"processes": 3' mpi3/summary.json
  rm -rf mpi$n
  $mpirun -np $n "$owsim" run hellas.yaml --frames 30 --threads 1 --outputs d64,summary,detections \
    --out hellas$n --quiet
  $same ref_hellas hellas$n
done

# flight.mcap (issue 47): each process builds its frames' chunks, process 0 appends them in frame
# order: flight.mcap and metadata.yaml are one process's bytes, whatever the threads. --resume with
# mcap is refused, in one line.
"$owsim" run "$source/examples/corridor.yaml" --frames 30 --threads 2 --outputs mcap,d64 \
  --out ref_mcap --quiet
$mpirun -np 2 "$owsim" run "$source/examples/corridor.yaml" --frames 30 --threads 1 \
  --outputs mcap,d64 --out mcap2 --quiet
$same ref_mcap mcap2
cmp ref_mcap/flight.mcap mcap2/flight.mcap
cmp ref_mcap/metadata.yaml mcap2/metadata.yaml
if $mpirun -np 2 "$owsim" run "$source/examples/corridor.yaml" --frames 30 --outputs mcap,d64 \
     --out mcap_resumed --resume > mcap_resume.log 2>&1; then
  echo "FAIL: --resume with mcap ran"; exit 1
fi
lines=$(grep -c '^owsim:' mcap_resume.log)
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines error lines"; cat mcap_resume.log; exit 1; fi
grep '^owsim: --resume: flight.mcap (output mcap) cannot be continued' mcap_resume.log

# A process killed after the first checkpoint ends the job; --resume with 3 processes completes it.
# Every output but points.csv (the same points as las and ply, 290 MB a copy over the whole flight).
full=d64,las,ply,trajectory,summary,truth,quicklook
"$owsim" run "$source/examples/corridor.yaml" --threads 2 --outputs $full --out ref_full --quiet
$mpirun -np 2 "$owsim" run "$source/examples/corridor.yaml" --threads 1 --outputs $full \
  --out killed --quiet > killed.log 2>&1 &
job=$!
tries=0
while [ ! -f killed/.owsim-resume ]; do
  tries=$((tries + 1))
  if [ $tries -gt 600 ]; then echo "FAIL: no checkpoint after 60 s"; exit 1; fi
  sleep 0.1
done
victim=$(pgrep -n -f "owsim run .*--out killed")
kill -9 "$victim"
if wait $job; then echo "FAIL: the job succeeded although a process was killed"; exit 1; fi
if [ -f killed/flight.d64 ] || [ -f killed/summary.json ]; then
  echo "FAIL: a killed job left a file under its final name"; exit 1
fi
$mpirun -np 3 "$owsim" run "$source/examples/corridor.yaml" --threads 1 --outputs $full \
  --out killed --resume 2> resumed.log
grep -E 'resuming .* at frame [1-9]' resumed.log
$same ref_full killed

# Bad input: every process meets it, one line says it.
if $mpirun -np 2 "$owsim" run "$source/examples/corridor.yaml" --frames 300 --out bad \
     > bad.log 2>&1; then
  echo "FAIL: a bad --frames ran"; exit 1
fi
lines=$(grep -c '^owsim:' bad.log)
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines error lines"; cat bad.log; exit 1; fi
grep '^owsim:.*only [0-9]* frames fit' bad.log
# Passed: the flights' outputs (~600 MB) go; a failure leaves them for a look.
cd /
rm -rf "$work"
echo "mpi_run: ok"
