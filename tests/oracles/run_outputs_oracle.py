#!/usr/bin/python3
"""Independent checks of an `owsim run` output folder, for tests/test_run_outputs.cpp.

Usage: run_outputs_oracle.py SETUP.json
SETUP.json (written by the test from the scenario's own numbers):
  {"points_csv": path, "trajectory_csv": path,
   "origin": {"lat": deg, "lon": deg, "h": m}, "flat_u": m,
   "divergence_mrad": full angle, "beam_exit_radius_m": m,
   "conductors": [{"id": "<span>/<n>", "from": [e, n], "to": [e, n],
                   "support_1_m": H1, "support_2_m": H2, "lowest_m": S,   # absolute local u
                   "lateral_m": dy, "radius_m": r}]}
Prints one JSON object of measured figures; the C++ test decides what passes.

- Geodetic: lat/lon/h of every point and trajectory row → ECEF with pyproj (EPSG:4979 →
  EPSG:4978), minus the origin's ECEF, rotated into East-North-Up at the origin; compared with
  the e/n/u columns.
- Ground: |u − flat_u| of every ground point.
- Wires: each wire point's distance to the analytic catenary of its conductor, solved here with
  scipy's brentq from the span's support heights, lowest point and length (y = a·cosh(x/a)
  shape, SENSOR-SPEC §6), minus the capture distance r_wire + r_beam(range),
  r_beam = exit radius + range · tan(divergence / 2) (SENSOR-SPEC §7).
"""
import csv
import json
import math
import sys

import numpy as np
import pyproj
from scipy.optimize import brentq


def read_csv_columns(path, names):
    with open(path, newline="") as file:
        reader = csv.reader(file)
        header = next(reader)
        index = [header.index(name) for name in names]
        rows = [[row[i] for i in index] for row in reader]
    return rows


def enu_from_geodetic(lat, lon, h, origin):
    to_ecef = pyproj.Transformer.from_crs("EPSG:4979", "EPSG:4978")
    x, y, z = to_ecef.transform(np.asarray(lat), np.asarray(lon), np.asarray(h))
    x0, y0, z0 = to_ecef.transform(origin["lat"], origin["lon"], origin["h"])
    phi, lam = math.radians(origin["lat"]), math.radians(origin["lon"])
    rotation = np.array([
        [-math.sin(lam), math.cos(lam), 0.0],
        [-math.sin(phi) * math.cos(lam), -math.sin(phi) * math.sin(lam), math.cos(phi)],
        [math.cos(phi) * math.cos(lam), math.cos(phi) * math.sin(lam), math.sin(phi)],
    ])
    d = np.vstack([np.asarray(x) - x0, np.asarray(y) - y0, np.asarray(z) - z0])
    return (rotation @ d).T


def geodetic_error_m(path, origin):
    rows = read_csv_columns(path, ["lat_deg", "lon_deg", "h_m", "e_m", "n_m", "u_m"])
    if not rows:
        return 0.0, 0
    values = np.array(rows, dtype=float)
    enu = enu_from_geodetic(values[:, 0], values[:, 1], values[:, 2], origin)
    return float(np.max(np.linalg.norm(enu - values[:, 3:6], axis=1))), len(rows)


class Catenary:
    """z(x) = S + a·(cosh((x − x0)/a) − 1) through (0, H1) and (D, H2) with minimum S."""

    def __init__(self, span_m, h1, h2, lowest):
        self.span_m = span_m
        self.lowest = lowest
        d1, d2 = h1 - lowest, h2 - lowest

        def a_for(x0):  # the a that puts support 1 on the curve with the vertex at x0
            if x0 <= 0.0:
                return math.inf
            g = lambda a: a * (math.cosh(x0 / a) - 1.0) - d1
            return brentq(g, x0 / 700.0, 1e12, xtol=1e-12, rtol=1e-15, maxiter=2000)

        def miss(x0):  # support 2's height above the curve's, for the vertex at x0
            a = a_for(x0)
            z = (span_m - x0) / a
            return 1e300 if z > 700 else a * (math.cosh(z) - 1.0) - d2

        if d1 == 0.0 and d2 == 0.0:
            raise ValueError("a catenary needs supports above its lowest point")
        self.x0 = brentq(miss, span_m * 1e-9, span_m * (1 - 1e-9), xtol=1e-12, rtol=1e-15,
                         maxiter=2000)
        self.a = a_for(self.x0)

    def z(self, x):
        return self.lowest + self.a * (np.cosh((x - self.x0) / self.a) - 1.0)

    def dz(self, x):
        return np.sinh((x - self.x0) / self.a)

    def ddz(self, x):
        return np.cosh((x - self.x0) / self.a) / self.a

    def distance_m(self, x, lateral, z):
        """Distance from points (x along, lateral across, z up) to the curve: Newton on the
        foot point x' where (x' − x) + (z(x') − z)·z'(x') = 0, clamped to the span."""
        xf = np.array(x, dtype=float)
        for _ in range(30):
            g = (xf - x) + (self.z(xf) - z) * self.dz(xf)
            dg = 1.0 + self.dz(xf) ** 2 + (self.z(xf) - z) * self.ddz(xf)
            xf = xf - g / dg
        xf = np.clip(xf, 0.0, self.span_m)
        return np.sqrt((x - xf) ** 2 + lateral ** 2 + (z - self.z(xf)) ** 2)


def wire_figures(setup):
    rows = read_csv_columns(setup["points_csv"], ["class", "object", "range_m", "e_m", "n_m", "u_m"])
    by_id = {c["id"]: c for c in setup["conductors"]}
    half_angle = 0.5 * setup["divergence_mrad"] * 1e-3
    worst_excess = -math.inf
    worst_ratio = 0.0
    count = 0
    unknown = set()
    groups = {}
    for cls, obj, rng, e, n, u in rows:
        if cls != "wire":
            continue
        count += 1
        if obj not in by_id:
            unknown.add(obj)
            continue
        groups.setdefault(obj, []).append((float(rng), float(e), float(n), float(u)))
    for obj, points in groups.items():
        c = by_id[obj]
        start = np.array(c["from"], dtype=float)
        along = np.array(c["to"], dtype=float) - start
        span_m = float(np.linalg.norm(along))
        forward = along / span_m
        right = np.array([forward[1], -forward[0]])
        start = start + c["lateral_m"] * right
        curve = Catenary(span_m, c["support_1_m"], c["support_2_m"], c["lowest_m"])
        p = np.array(points)
        rel = p[:, 1:3] - start
        distance = curve.distance_m(rel @ forward, rel @ right, p[:, 3])
        capture = c["radius_m"] + setup["beam_exit_radius_m"] + p[:, 0] * math.tan(half_angle)
        worst_excess = max(worst_excess, float(np.max(distance - capture)))
        worst_ratio = max(worst_ratio, float(np.max(distance / capture)))
    return {"wire_rows": count, "wire_conductors_hit": len(groups),
            "wire_max_excess_m": worst_excess if count else None,
            "wire_max_distance_over_capture": worst_ratio, "wire_unknown_objects": sorted(unknown)}


def ground_figures(setup):
    rows = read_csv_columns(setup["points_csv"], ["class", "u_m"])
    du = [abs(float(u) - setup["flat_u"]) for cls, u in rows if cls == "ground"]
    return {"ground_rows": len(du), "ground_max_abs_du_m": max(du) if du else None}


def main():
    with open(sys.argv[1]) as file:
        setup = json.load(file)
    figures = {}
    error, rows = geodetic_error_m(setup["points_csv"], setup["origin"])
    figures.update({"point_rows": rows, "point_geodetic_max_error_m": error})
    error, rows = geodetic_error_m(setup["trajectory_csv"], setup["origin"])
    figures.update({"trajectory_rows": rows, "trajectory_geodetic_max_error_m": error})
    figures.update(ground_figures(setup))
    figures.update(wire_figures(setup))
    print(json.dumps(figures))


if __name__ == "__main__":
    main()
