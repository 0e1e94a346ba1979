"""Exits 0 if two output folders of owsim hold the same outputs, byte for byte: every file of
the first is in the second with the same bytes, and the second has no other; summary.json files
are compared as JSON without the run's own facts (wall time, speed, threads, processes), which
say how a run went, not what it computed. Hidden files (checkpoints, sweep state) are skipped.

    same_outputs.py DIR_A DIR_B
"""
import json
import os
import sys

RUN_FACTS = ("setup_s", "wall_s", "pulses_per_s", "realtime_factor", "threads", "processes")


def files(root):
    found = set()
    for folder, _, names in os.walk(root):
        for name in names:
            if not name.startswith("."):
                found.add(os.path.relpath(os.path.join(folder, name), root))
    return found


def summary(path):
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    for key in RUN_FACTS:
        data.pop(key, None)
    return data


def main(a, b):
    in_a, in_b = files(a), files(b)
    problems = [f"only in {a}: {p}" for p in sorted(in_a - in_b)]
    problems += [f"only in {b}: {p}" for p in sorted(in_b - in_a)]
    for path in sorted(in_a & in_b):
        pa, pb = os.path.join(a, path), os.path.join(b, path)
        if os.path.basename(path) == "summary.json":
            same = summary(pa) == summary(pb)
        else:
            with open(pa, "rb") as fa, open(pb, "rb") as fb:
                same = fa.read() == fb.read()
        if not same:
            problems.append(f"differs: {path}")
    for problem in problems:
        print(problem)
    print(f"{len(in_a & in_b)} files compared, {len(problems)} problems")
    return 1 if problems or not in_a else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
