#!/usr/bin/python3
"""An independent recount of `owsim roc`, for tests/test_roc.cpp.

Usage: roc_oracle.py SWEEP_FOLDER ROC_FOLDER KEY LO HI RETURNS WINDOW_S CONFIDENCE TARGET
TARGET is an object id or class:CLASS. Straight from docs/evidence.md, with no code shared with
owsim: groups the members of SWEEP_FOLDER/sweep.csv by their value of KEY (as numbers when every
value is one), recounts each group's windows whose first frame's range lies in [LO, HI) from the
members' truth.csv and summary.json with numpy, sums their pulses and false returns
(summary.json returns.noise, 0 when absent) over their flight seconds (frames x frame period),
recomputes the Clopper-Pearson bounds with scipy.stats.beta.ppf, and compares every cell of
ROC_FOLDER/roc.csv (counts exactly, numbers to 1e-9 relative), roc.json's rows, and roc.svg
(well-formed XML, one point per value with windows, labelled with the value). Prints
"roc oracle: V values, W windows agree" and exits 0, or names the first difference and exits 1.
"""
import csv
import json
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

import numpy as np

from evidence_recount import clopper_pearson, target_rows


def number(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def members(folder, key):
    with open(os.path.join(folder, "sweep.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    digits = len(str(max(len(rows) - 1, 0)))
    return [(os.path.join(folder, str(int(r["member"])).zfill(digits)), r[key]) for r in rows]


def windows_of(flight, target, lo, hi, returns, window_s):
    """(windows, detected) of the target's windows starting in [lo, hi) in one flight."""
    with open(os.path.join(flight, "summary.json")) as f:
        summary = json.load(f)
    frames = summary["frames"]
    n = max(1, math.floor(window_s / summary["frame_period_s"] + 1e-9))
    by_object = target_rows(flight, target)
    windows = detected = 0
    for rows in by_object.values():
        per_frame = np.zeros(frames + n + 1, dtype=np.int64)
        for r in rows:
            per_frame[int(r["frame"])] += int(r["returns"])
        sums = np.concatenate(([0], np.cumsum(per_frame)))
        for r in rows:
            f = int(r["frame"])
            if r["in_view"] != "1" or f + n > frames:
                continue
            if lo <= float(r["range_m"]) < hi:
                windows += 1
                detected += int(sums[f + n] - sums[f] >= returns)
    noise = summary["returns"].get("noise", 0)
    return windows, detected, summary["pulses"], noise, frames * summary["frame_period_s"]


def expected_rows(sweep, key, lo, hi, returns, window_s, confidence, target):
    listed = members(sweep, key)
    numeric = all(number(v) is not None for _, v in listed)
    groups = {}
    for flight, value in listed:
        group = groups.setdefault(number(value) if numeric else value,
                                  {"value": value, "counts": np.zeros(6)})
        group["counts"] += np.array(windows_of(flight, target, lo, hi, returns, window_s) + (1,))
    rows = []
    for sort_key in sorted(groups):
        g = groups[sort_key]
        w, k, pulses, noise, seconds, count = g["counts"].tolist()
        lo_b, hi_b = clopper_pearson(int(k), int(w), confidence)
        rows.append({"value": g["value"], "members": int(count), "windows": int(w),
                     "windows_detected": int(k), "pd_window": k / w if w else math.nan,
                     "pd_window_lo": lo_b, "pd_window_hi": hi_b, "pulses": int(pulses),
                     "false_returns": int(noise), "false_returns_per_s": noise / seconds})
    return rows


def close(got, want, what):
    if isinstance(want, float) and math.isnan(want):
        if got not in ("", None):
            raise ValueError(f"{what} is {got!r}, expected empty")
        return
    if isinstance(want, int):
        if int(got) != want:
            raise ValueError(f"{what} is {got}, expected {want}")
        return
    if abs(float(got) - want) > 1e-9 * max(1.0, abs(want)):
        raise ValueError(f"{what} is {got}, expected {want!r}")


def main():
    sweep, out, key, lo, hi, returns, window_s, confidence, target = sys.argv[1:10]
    rows = expected_rows(sweep, key, float(lo), float(hi), int(returns), float(window_s),
                         float(confidence), target)
    with open(os.path.join(out, "roc.csv"), newline="") as f:
        got = list(csv.DictReader(f))
    with open(os.path.join(out, "roc.json")) as f:
        document = json.load(f)
    svg = ElementTree.parse(os.path.join(out, "roc.svg")).getroot()
    try:
        if len(got) != len(rows) or len(document["rows"]) != len(rows):
            raise ValueError(f"{len(got)} csv rows, {len(document['rows'])} json rows, "
                             f"expected {len(rows)}")
        for want, row, entry in zip(rows, got, document["rows"]):
            if row["value"] != want["value"]:
                raise ValueError(f"value {row['value']!r}, expected {want['value']!r}")
            for name, value in want.items():
                if name == "value":
                    continue
                close(row[name], value, f"roc.csv {want['value']} {name}")
                close(entry[name], value, f"roc.json {want['value']} {name}")
        if document["by"] != key or document["target"] != target:
            raise ValueError(f"roc.json names {document['by']}, {document['target']}")
        ns = "{http://www.w3.org/2000/svg}"
        points = [c.get("data-value") for c in svg.iter(ns + "circle")
                  if c.get("class") == "roc-point"]
        plotted = [r["value"] for r in rows if r["windows"] > 0]
        if points != plotted:
            raise ValueError(f"roc.svg points {points}, expected {plotted}")
        labels = [t.text for t in svg.iter(ns + "text")]
        for value in plotted:
            if value not in labels:
                raise ValueError(f"roc.svg has no label {value}")
    except ValueError as e:
        print("roc oracle:", e)
        return 1
    print(f"roc oracle: {len(rows)} values, {sum(r['windows'] for r in rows)} windows agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
