"""How owsim scales over processes and threads (issue 18), measured in one sitting: the corridor
flight (words only, and every output) and the 20-member corridor sweep, each as 1 process × 1
thread, 1 process × 2 threads and 2 processes × 1 thread (mpirun), repeated, medians reported;
beside the runs, two separate one-thread runs at once (no MPI), for what two processes get from
the machine at all.

For each: pulses/s inside the run (summary.json's pulses_per_s, aggregated over the processes;
for a sweep, all members' pulses over its wall time), the whole command's wall time (process
start, MPI start-up and set-up included), the parallel efficiency (pulses/s over workers × the
1 × 1 figure) and the output bytes written per second of the whole command.

    /usr/bin/python3 bench/distributed_scaling.py [--owsim build/owsim] [--repeat 3]
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none"]
SHAPES = [(1, 1), (1, 2), (2, 1)]  # processes, threads
SEPARATE = "2 separate × 1"  # two one-thread runs at once without MPI: what the machine allows


def folder_bytes(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path) for f in files)


def command(owsim, processes, threads, arguments):
    base = [owsim] + arguments + ["--threads", str(threads), "--quiet"]
    return MPIRUN + ["-np", str(processes)] + base if processes > 1 else base


def run_once(owsim, processes, threads, kind, out):
    shutil.rmtree(out, ignore_errors=True)
    if kind == "sweep":
        arguments = ["sweep", os.path.join(ROOT, "examples/corridor_sweep.yaml"),
                     "--out", out]
    else:
        outputs = "d64,summary" if kind == "run: words" else "d64,points,trajectory,summary"
        arguments = ["run", os.path.join(ROOT, "examples/corridor.yaml"), "--out", out,
                     "--outputs", outputs]
    argv = command(owsim, processes, threads, arguments)
    if kind == "sweep":
        argv.remove("--quiet")  # its last line says the aggregate pulses/s
    start = time.perf_counter()
    done = subprocess.run(argv, capture_output=True, text=True, check=True)
    wall = time.perf_counter() - start
    if kind == "sweep":
        rate = float(re.search(r"\(([0-9.]+) pulses/s", done.stderr.splitlines()[-1]).group(1))
    else:
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            rate = json.load(f)["pulses_per_s"]
    return rate, wall, folder_bytes(out)


def run_separately(owsim, kind, out):
    """Two one-thread runs of the flight at once, each its own process: their summed pulses/s."""
    outputs = "d64,summary" if kind == "run: words" else "d64,points,trajectory,summary"
    folders = [out + "_a", out + "_b"]
    for folder in folders:
        shutil.rmtree(folder, ignore_errors=True)
    start = time.perf_counter()
    children = [subprocess.Popen([owsim, "run", os.path.join(ROOT, "examples/corridor.yaml"),
                                  "--out", folder, "--outputs", outputs, "--threads", "1",
                                  "--quiet"]) for folder in folders]
    if any(child.wait() != 0 for child in children):
        raise RuntimeError("a separate run failed")
    wall = time.perf_counter() - start
    rate = 0.0
    for folder in folders:
        with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
            rate += json.load(f)["pulses_per_s"]
    return rate, wall, sum(folder_bytes(folder) for folder in folders)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--owsim", default=os.path.join(ROOT, "build", "owsim"))
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    if shutil.which("mpirun") is None:
        sys.exit("distributed_scaling: mpirun not found (scripts/setup.sh installs OpenMPI)")
    work = tempfile.mkdtemp(prefix="owsim_scaling_")
    print(f"# {os.cpu_count()} cores; medians of {args.repeat} runs, configurations interleaved\n")
    print("| workload | processes × threads | pulses/s in the run | efficiency | "
          "command wall s | output MB/s |")
    print("|---|---|---|---|---|---|")
    try:
        for kind in ("run: words", "run: every output", "sweep"):
            samples = {shape: [] for shape in SHAPES}
            separate = []
            for _ in range(args.repeat):
                for shape in SHAPES:
                    samples[shape].append(
                        run_once(args.owsim, *shape, kind, os.path.join(work, "out")))
                if kind != "sweep":
                    separate.append(run_separately(args.owsim, kind, os.path.join(work, "out")))
            single = statistics.median(s[0] for s in samples[(1, 1)])
            for processes, threads in SHAPES:
                rate = statistics.median(s[0] for s in samples[(processes, threads)])
                wall = statistics.median(s[1] for s in samples[(processes, threads)])
                size = samples[(processes, threads)][0][2]
                efficiency = rate / (processes * threads * single)
                print(f"| {kind} | {processes} × {threads} | {rate / 1e6:.2f} M | "
                      f"{efficiency:.2f} | {wall:.2f} | {size / wall / 1e6:.0f} |")
            if separate:
                rate = statistics.median(s[0] for s in separate)
                wall = statistics.median(s[1] for s in separate)
                print(f"| {kind} | {SEPARATE} | {rate / 1e6:.2f} M | {rate / (2 * single):.2f} | "
                      f"{wall:.2f} | {separate[0][2] / wall / 1e6:.0f} |")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
