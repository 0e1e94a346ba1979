"""How owsim's cost grows with the size of the scene, measured in one sitting: the corridor flight
over a growing forest (400 to 1,000,000 trees) and over a growing grid of seven-conductor spans
(10 to 5,000 spans over 4 × 4 km), the scenes generated into a temporary folder.

For each scene, two runs of the whole command: a loop run (60 frames, words and summary only)
and a first-frame run (1 frame, every output). Reported per scene: the objects in the scene
(summary.json's objects), the set-up time (summary.json's setup_s: reading the scenario, building
the scene, the BVH and the simulator, opening the outputs), the first-frame run's wall
time, the peak memory of each run (the child's own ru_maxrss, from os.wait4), the loop's
pulses/s (summary.json's pulses_per_s) and the loop run's summary.json size. MB are 10^6 bytes.
With --repeat R > 1, each figure is the median of R runs.

    /usr/bin/python3 bench/scene_size.py [--owsim build/owsim] [--frames 60] [--repeat 1]
                                         [--only forest|grid] [--sizes 400,4000] [--json FILE]
"""
import argparse
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORRIDOR = os.path.join(ROOT, "examples", "corridor.yaml")
SIZES = {"forest": [400, 4000, 40000, 400000, 1000000],  # trees
         "grid": [10, 100, 1000, 5000]}  # spans
LOOP_OUTPUTS = "d64,summary"

# The grid: lines of 200 m spans across [-2000, 2000] m, alternately east-west and north-south.
SPAN_M = 200.0
HALF_M = 2000.0
SPANS_PER_LINE = int(2 * HALF_M / SPAN_M)
LINE_HEIGHTS = {"ew": (30, 22), "ns": (45, 36)}  # support heights, lowest point (m)


def corridor_text():
    with open(CORRIDOR, encoding="utf-8") as f:
        return f.read()


def forest_scene(trees):
    """The corridor with `trees` trees in its forest instead of 400."""
    text = corridor_text()
    old, new = "forest: {count: 400,", f"forest: {{count: {trees},"
    assert old in text, f"{CORRIDOR} no longer holds '{old}'"
    return text.replace(old, new)


def line_offsets(count):
    """Offsets of `count` parallel lines from the centre outwards: 0, +s, −s, +2s, −2s, …,
    s = 4000 m / count. With an even count the last one is +2000 m, the area's edge."""
    step = 2 * HALF_M / count if count else 0.0
    offsets = [0.0]
    k = 1
    while len(offsets) < count:
        offsets += [k * step, -k * step]
        k += 1
    return offsets[:count]


def grid_lines(spans):
    """(direction, offset) of each line, east-west and north-south lines alternating, enough
    lines of SPANS_PER_LINE spans for `spans` spans (the east-west ones one more if odd)."""
    lines = math.ceil(spans / SPANS_PER_LINE)
    east_west = line_offsets(math.ceil(lines / 2))
    north_south = line_offsets(lines // 2)
    order = []
    for i in range(len(east_west)):
        order.append(("ew", east_west[i]))
        if i < len(north_south):
            order.append(("ns", north_south[i]))
    return order


def span_line(line, k, direction, offset):
    """The YAML line of span k of a line: 200 m along it, seven conductors (sept), no supports."""
    start = -HALF_M + k * SPAN_M
    along = (start, start + SPAN_M)
    if direction == "ew":  # along e at n = offset
        (e0, n0), (e1, n1) = (along[0], offset), (along[1], offset)
    else:  # along n at e = offset
        (e0, n0), (e1, n1) = (offset, along[0]), (offset, along[1])
    height, lowest = LINE_HEIGHTS[direction]
    return (f"    - {{id: l{line}-{k}, from: {{e: {e0:g}, n: {n0:g}}}, "
            f"to: {{e: {e1:g}, n: {n1:g}}}, support_heights_m: [{height:g}, {height:g}], "
            f"lowest_point_m: {lowest:g}, layout: sept, "
            f"conductor: {{diameter_mm: 21, reflectivity: 0.4}}, supports: {{kind: none}}}}")


def grid_scene(spans):
    """The corridor's header (flight, sensor, terrain) over a grid of `spans` spans; the
    corridor's own spans, poles and forest are dropped."""
    text = corridor_text()
    assert "  spans:" in text and "name: corridor" in text, f"{CORRIDOR} changed shape"
    header = text[:text.index("  spans:")].replace("name: corridor", "name: grid")
    lines = []
    for line, (direction, offset) in enumerate(grid_lines(spans)):
        for k in range(SPANS_PER_LINE):
            if len(lines) == spans:
                break
            lines.append(span_line(line, k, direction, offset))
    return header + "  spans:\n" + "\n".join(lines) + "\n"


def write_scene(work, kind, size):
    path = os.path.join(work, f"{kind}_{size}.yaml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(forest_scene(size) if kind == "forest" else grid_scene(size))
    return path


def run_measured(argv, out):
    """Run argv afresh into `out`: its wall time (s) and the child's own peak RSS (bytes)."""
    shutil.rmtree(out, ignore_errors=True)
    with tempfile.TemporaryFile() as stderr_file:
        start = time.perf_counter()
        child = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=stderr_file)
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.perf_counter() - start
        child.returncode = os.waitstatus_to_exitcode(status)
        if child.returncode != 0:
            stderr_file.seek(0)
            sys.exit(f"scene_size: exit status {child.returncode} from {' '.join(argv)}\n"
                     + stderr_file.read().decode(errors="replace"))
    return wall, usage.ru_maxrss * 1024  # ru_maxrss is in KB on Linux


def loop_run(owsim, scene, frames, out):
    wall, peak = run_measured([owsim, "run", scene, "--frames", str(frames),
                               "--outputs", LOOP_OUTPUTS, "--out", out, "--quiet"], out)
    summary_path = os.path.join(out, "summary.json")
    head = summary_head(summary_path)
    objects = sum(c["objects"] for c in head["objects_by_class"].values())
    return {"wall_s": wall, "peak": peak, "pulses_per_s": head["pulses_per_s"],
            "setup_s": head["setup_s"], "objects": objects,
            "summary_bytes": os.path.getsize(summary_path)}


def summary_head(path):
    """summary.json without its objects array, which comes last: the totals of a million-object
    summary without loading it. (Loading it would also grow this process to several times the
    file, and a child started later by vfork inherits that high-water mark as its peak RSS.)"""
    with open(path, encoding="utf-8") as f:
        text = f.read(1 << 16)
    cut = text.find(',\n  "objects": [')
    if cut < 0:
        sys.exit(f"scene_size: {path}: no objects array after the totals")
    return json.loads(text[:cut] + "\n}")


def first_frame_run(owsim, scene, out):
    wall, peak = run_measured([owsim, "run", scene, "--frames", "1", "--out", out, "--quiet"], out)
    return {"wall_s": wall, "peak": peak}


def median_of(samples, key):
    values = [s[key] for s in samples if s[key] is not None]
    return statistics.median(values) if values else None


def measure_scene(owsim, kind, size, frames, repeat, work):
    """Both runs of one scene, `repeat` times: one row of medians."""
    scene = write_scene(work, kind, size)
    loops, firsts = [], []
    for attempt in range(1, repeat + 1):
        loops.append(loop_run(owsim, scene, frames, os.path.join(work, "x")))
        print(f"scene_size: {kind} {size} [{attempt}/{repeat}] loop run: "
              f"{loops[-1]['wall_s']:.2f} s, {loops[-1]['peak'] / 1e6:.0f} MB peak, "
              f"{loops[-1]['pulses_per_s'] / 1e6:.2f} M pulses/s", file=sys.stderr, flush=True)
        firsts.append(first_frame_run(owsim, scene, os.path.join(work, "y")))
        print(f"scene_size: {kind} {size} [{attempt}/{repeat}] first-frame run: "
              f"{firsts[-1]['wall_s']:.2f} s, {firsts[-1]['peak'] / 1e6:.0f} MB peak",
              file=sys.stderr, flush=True)
    for folder in ("x", "y"):
        shutil.rmtree(os.path.join(work, folder), ignore_errors=True)
    os.remove(scene)
    return {"scene": f"{kind} {size}", "kind": kind, "size": size,
            "objects": loops[0]["objects"],
            "setup_s": median_of(loops, "setup_s"),
            "first_frame_wall_s": median_of(firsts, "wall_s"),
            "first_frame_peak_mb": median_of(firsts, "peak") / 1e6,
            "loop_peak_mb": median_of(loops, "peak") / 1e6,
            "loop_pulses_per_s": median_of(loops, "pulses_per_s"),
            "summary_mb": median_of(loops, "summary_bytes") / 1e6,
            "frames": frames, "repeat": repeat}


def table_row(row):
    setup = "—" if row["setup_s"] is None else f"{row['setup_s']:.3f}"
    return (f"| {row['scene']} | {row['objects']:,} | {setup} | {row['first_frame_wall_s']:.3f} | "
            f"{row['first_frame_peak_mb']:.0f} | {row['loop_peak_mb']:.0f} | "
            f"{row['loop_pulses_per_s'] / 1e6:.2f} M | {row['summary_mb']:.2f} |")


def parse_sizes(text):
    try:
        sizes = [int(size) for size in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a comma-separated list of whole numbers: {text}")
    if any(size <= 0 for size in sizes):
        raise argparse.ArgumentTypeError("sizes must be positive")
    return sizes


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--owsim", default=os.path.join(ROOT, "build", "owsim"))
    parser.add_argument("--frames", type=int, default=60, help="frames of the loop run")
    parser.add_argument("--repeat", type=int, default=1, help="runs per scene, medians reported")
    parser.add_argument("--only", choices=sorted(SIZES), help="one kind of scene only")
    parser.add_argument("--sizes", type=parse_sizes,
                        help="comma-separated sizes of the --only kind (trees or spans)")
    parser.add_argument("--json", metavar="FILE", help="also write the rows as JSON")
    args = parser.parse_args()
    if args.sizes and not args.only:
        parser.error("--sizes needs --only forest|grid")
    if args.frames < 1 or args.repeat < 1:
        parser.error("--frames and --repeat must be at least 1")
    if not os.access(args.owsim, os.X_OK):
        sys.exit(f"scene_size: no owsim binary at {args.owsim} (build it, or pass --owsim)")
    kinds = [args.only] if args.only else list(SIZES)
    work = tempfile.mkdtemp(prefix="owsim_scene_size_")
    rows = []
    print(f"# {os.cpu_count()} cores; loop run {args.frames} frames ({LOOP_OUTPUTS}), "
          f"first-frame run 1 frame (every output); medians of {args.repeat} run(s)\n")
    print("| scene | objects | set-up s | first-frame run wall s | first-frame peak MB | "
          "loop-run peak MB | loop pulses/s | summary.json MB |")
    print("|---|---|---|---|---|---|---|---|")
    try:
        for kind in kinds:
            for size in args.sizes or SIZES[kind]:
                rows.append(measure_scene(args.owsim, kind, size, args.frames, args.repeat, work))
                print(table_row(rows[-1]), flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
        if args.json and rows:
            with open(args.json, "w", encoding="utf-8") as f:
                json.dump(rows, f, indent=2)
                f.write("\n")


if __name__ == "__main__":
    main()
