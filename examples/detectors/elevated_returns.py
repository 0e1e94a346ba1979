#!/usr/bin/python3
"""A simple, honest reference detector for owsim's point clouds (README "Detection evidence").

    elevated_returns.py RUN_DIR OUT.csv          one flight: points.csv → detections
    elevated_returns.py SWEEP_DIR OUT_FOLDER     every member → OUT_FOLDER/<member>.csv

It sees only what the sensor and the navigation give — each return's time and position (frame,
time_s, e_m, n_m, u_m of points.csv) — never the class or object columns, which are the truth it
is scored against. Per flight it estimates the ground as the lowest return in each 20 m cell; per
frame it keeps returns more than 4 m above that ground, bins them into 8 m cells and reports each
cell with at least two such returns as one detection at their centroid, classed by shape: `pole`
when the returns span more than 6 m in height but less than 2.5 m across, `wire` when they lie
within 1.5 m of each other in height and more than 10 m above the ground, otherwise `tree`.
numpy only.

Honest about what it misses: a wire seen by a single return a frame (far away) is not reported,
two wires within one cell become one detection, and canopy edges are reported as trees.
Output columns: time_s,e_m,n_m,u_m,class,track (track empty: no tracking).
"""
import csv
import os
import sys

import numpy as np

GROUND_CELL_M = 20.0
OBSTACLE_CELL_M = 8.0
MIN_HEIGHT_M = 4.0


def read_points(path):
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    columns = [header.index(name) for name in ("frame", "time_s", "e_m", "n_m", "u_m")]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=columns, ndmin=2)
    return data


def detect(points):
    """One row per detection: time_s, e_m, n_m, u_m, class."""
    if len(points) == 0:
        return []
    frame, time, e, n, u = points.T
    # The ground: the lowest return of each 20 m cell over the whole flight.
    gx = np.floor(e / GROUND_CELL_M).astype(np.int64)
    gy = np.floor(n / GROUND_CELL_M).astype(np.int64)
    ground_key = gx * 1_000_003 + gy
    order = np.argsort(ground_key)
    keys, first = np.unique(ground_key[order], return_index=True)
    lowest = np.minimum.reduceat(u[order], first)
    ground = lowest[np.searchsorted(keys, ground_key)]
    height = u - ground
    elevated = height > MIN_HEIGHT_M
    # Per frame and 8 m cell: the elevated returns together.
    cx = np.floor(e[elevated] / OBSTACLE_CELL_M).astype(np.int64)
    cy = np.floor(n[elevated] / OBSTACLE_CELL_M).astype(np.int64)
    f = frame[elevated].astype(np.int64)
    key = np.stack([f, cx, cy], axis=1)
    groups, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    detections = []
    sums = {name: np.bincount(inverse, weights=values[elevated], minlength=len(groups))
            for name, values in (("t", time), ("e", e), ("n", n), ("u", u), ("h", height))}
    def extent(values):
        low = np.full(len(groups), np.inf)
        high = np.full(len(groups), -np.inf)
        np.minimum.at(low, inverse, values[elevated])
        np.maximum.at(high, inverse, values[elevated])
        return high - low

    u_span, e_span, n_span = extent(u), extent(e), extent(n)
    for g in range(len(groups)):
        if counts[g] < 2:
            continue
        span = u_span[g]
        mean_height = sums["h"][g] / counts[g]
        if span > 6.0 and max(e_span[g], n_span[g]) < 2.5:
            kind = "pole"
        elif span < 1.5 and mean_height > 10.0:
            kind = "wire"
        else:
            kind = "tree"
        detections.append((sums["t"][g] / counts[g], sums["e"][g] / counts[g],
                           sums["n"][g] / counts[g], sums["u"][g] / counts[g], kind))
    detections.sort()
    return detections


def write(path, detections):
    with open(path, "w", newline="") as f:
        out = csv.writer(f, lineterminator="\n")
        out.writerow(["time_s", "e_m", "n_m", "u_m", "class", "track"])
        for t, e, n, u, kind in detections:
            out.writerow([f"{t:.6f}", f"{e:.3f}", f"{n:.3f}", f"{u:.3f}", kind, ""])


def main(folder, out):
    table = os.path.join(folder, "sweep.csv")
    if not os.path.exists(table):
        write(out, detect(read_points(os.path.join(folder, "points.csv"))))
        return 0
    with open(table, newline="") as f:
        members = [int(row["member"]) for row in csv.DictReader(f)]
    digits = len(str(max(len(members) - 1, 0)))
    os.makedirs(out, exist_ok=True)
    for m in members:
        name = str(m).zfill(digits)
        write(os.path.join(out, name + ".csv"),
              detect(read_points(os.path.join(folder, name, "points.csv"))))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
