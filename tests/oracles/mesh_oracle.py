"""Independent check of mesh returns (scenario key scene.meshes, geometry/mesh_placement.hpp).

    mesh_oracle.py SPEC.json POINTS     every return of POINTS (points.csv) on a mesh of SPEC lies
                                        on that mesh's surface, placed here from the model file
                                        by this script's own reader; prints
                                        "ok <object>=<returns> ... <largest distance in mm>"

SPEC: {"origin": [lat, lon, h], "meshes": [{"id", "file", "at": {"e","n","u"} or
{"lat","lon","h"}, "yaw_deg", "scale", "up_axis": "z"|"y"}]}. A geodetic position is turned into
local ENU with pyproj (WGS-84 geodetic → geocentric) and the east-north-up rotation at the
origin. Models are read as OBJ (v / f lines, polygons fanned) or ASCII PLY (vertex x y z, face
lists). A return lies on the mesh when some triangle holds its foot point (barycentric slack
1e-6) within 2 mm of the plane: the points' 0.1 mm text plus the float vertices Embree traces.
"""
import csv
import json
import math
import sys

import numpy as np
from pyproj import Transformer


def read_obj(path):
    vertices, triangles = [], []
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            corners = [int(p.split("/")[0]) - 1 for p in parts[1:]]
            triangles += [[corners[0], corners[k], corners[k + 1]] for k in range(1, len(corners) - 1)]
    return np.array(vertices), triangles


def read_ply(path):
    lines = open(path).read().split("\n")
    end = lines.index("end_header")
    counts = {l.split()[1]: int(l.split()[2]) for l in lines[:end] if l.startswith("element")}
    body = [l.split() for l in lines[end + 1:] if l.strip()]
    n = counts["vertex"]
    vertices = np.array([[float(x) for x in row[:3]] for row in body[:n]])
    triangles = []
    for row in body[n:n + counts["face"]]:
        corners = [int(x) for x in row[1:1 + int(row[0])]]
        triangles += [[corners[0], corners[k], corners[k + 1]] for k in range(1, len(corners) - 1)]
    return vertices, triangles


def enu_of(origin, lat, lon, h):
    to_ecef = Transformer.from_crs("EPSG:4979", "EPSG:4978", always_xy=True)
    p = np.array(to_ecef.transform(lon, lat, h))
    o = np.array(to_ecef.transform(origin[1], origin[0], origin[2]))
    phi, lam = math.radians(origin[0]), math.radians(origin[1])
    rotation = np.array([[-math.sin(lam), math.cos(lam), 0.0],
                         [-math.sin(phi) * math.cos(lam), -math.sin(phi) * math.sin(lam), math.cos(phi)],
                         [math.cos(phi) * math.cos(lam), math.cos(phi) * math.sin(lam), math.sin(phi)]])
    return rotation @ (p - o)


def placed(spec, origin, folder):
    path = spec["file"] if spec["file"].startswith("/") else folder + "/" + spec["file"]
    vertices, triangles = (read_ply if path.endswith(".ply") else read_obj)(path)
    if spec.get("up_axis", "z") == "y":
        vertices = np.column_stack([vertices[:, 0], -vertices[:, 2], vertices[:, 1]])
    vertices = vertices * spec.get("scale", 1.0)
    yaw = math.radians(spec.get("yaw_deg", 0.0))
    # Clockwise seen from above by yaw: a heading-like turn, north towards east.
    turn = np.array([[math.cos(yaw), math.sin(yaw), 0.0], [-math.sin(yaw), math.cos(yaw), 0.0],
                     [0.0, 0.0, 1.0]])
    at = spec["at"]
    base = (np.array([at["e"], at["n"], at["u"]]) if "e" in at
            else enu_of(origin, at["lat"], at["lon"], at["h"]))
    return (vertices @ turn.T + base)[np.array(triangles)]


def distance_to_surface(point, corners):
    """The smallest |plane distance| over the triangles whose interior holds the foot point."""
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    normal = np.cross(b - a, c - a)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    offset = np.einsum("ij,ij->i", point - a, normal)
    foot = point - offset[:, None] * normal
    inside = np.ones(len(corners), dtype=bool)
    for p, q in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ij,ij->i", np.cross(q - p, foot - p), normal) >= -1e-6 * np.linalg.norm(q - p, axis=1)
    return np.min(np.abs(offset[inside])) if inside.any() else math.inf


def main(spec_path, points_path):
    spec = json.load(open(spec_path))
    folder = spec_path.rsplit("/", 1)[0]
    meshes = {m["id"]: placed(m, spec["origin"], folder) for m in spec["meshes"]}
    counts, worst = {name: 0 for name in meshes}, 0.0
    with open(points_path, newline="") as f:
        for row in csv.DictReader(f):
            if row["object"] not in meshes:
                continue
            point = np.array([float(row["e_m"]), float(row["n_m"]), float(row["u_m"])])
            distance = distance_to_surface(point, meshes[row["object"]])
            if distance > 0.002:
                sys.exit(f"return of frame {row['frame']} pulse {row['pulse']} on {row['object']} "
                         f"at {point} is {distance} m off the mesh")
            counts[row["object"]] += 1
            worst = max(worst, distance)
    print("ok " + " ".join(f"{name}={n}" for name, n in counts.items()) + f" {worst * 1000.0:.3f}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
