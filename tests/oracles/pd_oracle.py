#!/usr/bin/python3
"""An independent recount of `owsim pd`, for tests/test_evidence_cli.cpp.

Usage: pd_oracle.py FOLDER PD_CSV RETURNS WINDOW_S LO HI STEP CONFIDENCE TARGET
FOLDER is a run or sweep folder; TARGET an object id or class:CLASS. Recounts every bin's windows
and trials from the flights' truth.csv and summary.json with numpy, straight from the definitions
in docs/evidence.md (no code shared with owsim), recomputes the Clopper–Pearson bounds with
scipy.stats.beta.ppf, and compares them with pd.csv: counts exactly, proportions and bounds to
1e-9. Prints "pd oracle: N bins, W windows, T trials agree" and exits 0, or names the first
difference and exits 1.
"""
import csv
import json
import math
import os
import sys

import numpy as np

from evidence_recount import clopper_pearson, target_rows


def flights(folder):
    table = os.path.join(folder, "sweep.csv")
    if os.path.exists(table):
        with open(table, newline="") as f:
            members = [int(row["member"]) for row in csv.DictReader(f)]
        digits = len(str(max(len(members) - 1, 0)))
        return [os.path.join(folder, str(m).zfill(digits)) for m in members]
    return [folder]


def tracks(flight, target):
    """{object id: (frames, ranges, in_view, returns)} of the target's rows."""
    by_object = target_rows(flight, target)
    out = {}
    for obj, rows in by_object.items():
        out[obj] = (np.array([int(r["frame"]) for r in rows]),
                    np.array([float(r["range_m"]) for r in rows]),
                    np.array([r["in_view"] == "1" for r in rows]),
                    np.array([int(r["returns"]) for r in rows]))
    return out


def main():
    folder, pd_csv, returns, window_s, lo, hi, step, confidence, target = sys.argv[1:10]
    returns, window_s = int(returns), float(window_s)
    lo, hi, step, confidence = float(lo), float(hi), float(step), float(confidence)
    edges = np.arange(lo, hi, step)
    bins = len(edges)
    windows = np.zeros(bins, dtype=int)
    windows_hit = np.zeros(bins, dtype=int)
    trials = np.zeros(bins, dtype=int)
    trials_hit = np.zeros(bins, dtype=int)
    for flight in flights(folder):
        with open(os.path.join(flight, "summary.json")) as f:
            summary = json.load(f)
        frames_in_flight = summary["frames"]
        n = max(1, math.floor(window_s / summary["frame_period_s"] + 1e-9))
        for obj, (frames, ranges, in_view, rets) in tracks(flight, target).items():
            per_frame = dict(zip(frames.tolist(), rets.tolist()))
            first_detection = None
            for f, r, seen in zip(frames.tolist(), ranges.tolist(), in_view.tolist()):
                if not seen or f + n > frames_in_flight:
                    continue
                total = sum(per_frame.get(g, 0) for g in range(f, f + n))
                hit = total >= returns
                if hit and first_detection is None:
                    first_detection = r
                if lo <= r < hi:
                    b = min(int(math.floor((r - lo) / step)), bins - 1)
                    windows[b] += 1
                    windows_hit[b] += hit
            if not in_view.any():
                continue
            farthest = ranges[in_view].max()
            for b in range(bins):
                if farthest >= edges[b]:
                    trials[b] += 1
                    if first_detection is not None and first_detection >= edges[b]:
                        trials_hit[b] += 1
    with open(pd_csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if len(rows) != bins:
        print(f"pd oracle: {len(rows)} rows, expected {bins}")
        return 1

    def close(cell, value, what, b):
        if math.isnan(value):
            if cell != "":
                raise ValueError(f"bin {b}: {what} is {cell}, expected empty")
            return
        if abs(float(cell) - value) > 1e-9:
            raise ValueError(f"bin {b}: {what} is {cell}, expected {value!r}")

    try:
        for b, row in enumerate(rows):
            for name, value in (("windows", windows[b]), ("windows_detected", windows_hit[b]),
                                ("trials", trials[b]), ("trials_detected", trials_hit[b])):
                if int(row[name]) != value:
                    raise ValueError(f"bin {b}: {name} is {row[name]}, expected {value}")
            for prefix, k, n_ in (("pd_window", windows_hit[b], windows[b]),
                                  ("pd_cumulative", trials_hit[b], trials[b])):
                lo_b, hi_b = clopper_pearson(int(k), int(n_), confidence)
                close(row[prefix], k / n_ if n_ else math.nan, prefix, b)
                close(row[prefix + "_lo"], lo_b, prefix + "_lo", b)
                close(row[prefix + "_hi"], hi_b, prefix + "_hi", b)
    except ValueError as e:
        print("pd oracle:", e)
        return 1
    print(f"pd oracle: {bins} bins, {windows.sum()} windows, {trials.max()} trials agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
