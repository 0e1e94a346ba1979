"""Writes the data of examples/real_corridor.yaml (run from anywhere; needs only the standard
library): a DEM of rolling hills as an ESRI ASCII grid in UTM zone 32N (real_corridor_dem.asc with
its CRS in real_corridor_dem.prj, 40 m cells, heights above the WGS-84 ellipsoid, a NODATA pond),
the corridor's two power lines as GeoJSON LineStrings of towers (real_corridor_lines.geojson), and
a gabled barn as a Wavefront OBJ model in metres, z up, its origin at the middle of its ground
floor (real_corridor_barn.obj).
Positions are laid out in the example's local frame (origin 48.6881° N, 10.8447° E) and turned into
UTM and WGS-84 with the local-tangent approximation, which is plenty for made-up data.

    /usr/bin/python3 examples/data/make_real_corridor.py
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
LAT0, LON0, H0 = 48.6881, 10.8447, 450.0
A, F = 6378137.0, 1 / 298.257223563
E2 = F * (2 - F)
PHI = math.radians(LAT0)
M = A * (1 - E2) / (1 - E2 * math.sin(PHI) ** 2) ** 1.5   # metres per radian of latitude
N = A / math.sqrt(1 - E2 * math.sin(PHI) ** 2)             # prime vertical radius
# UTM zone 32N easting/northing of the origin (from pyproj, fixed here).
ORIGIN_UTM = (635_763.50, 5_394_426.16)
# The grid convergence at the origin (UTM north vs true north), radians.
CONVERGENCE = math.atan(math.tan(math.radians(LON0 - 9.0)) * math.sin(PHI))


def lon_lat(e, n):
    return [LON0 + math.degrees(e / (N * math.cos(PHI))), LAT0 + math.degrees(n / M)]


def height(e, n):
    """Rolling hills around the origin's height, a valley along the lines."""
    return (H0 + 14.0 * math.sin(e / 380.0) * math.cos(n / 290.0) + 6.0 * math.sin(n / 170.0 + 1.0)
            - 8.0 * math.exp(-(n / 250.0) ** 2))


def write_dem():
    cell, half_e, half_n = 40.0, 2700.0, 1700.0
    cols, rows = int(2 * half_e / cell) + 1, int(2 * half_n / cell) + 1
    x0, y0 = ORIGIN_UTM[0] - half_e, ORIGIN_UTM[1] - half_n
    lines = [f"ncols {cols}", f"nrows {rows}", f"xllcenter {x0:.1f}", f"yllcenter {y0:.1f}",
             f"cellsize {cell}", "NODATA_value -9999"]
    for r in range(rows):
        y = y0 + (rows - 1 - r) * cell
        row = []
        for c in range(cols):
            x = x0 + c * cell
            # UTM offsets → local east/north (rotate by the grid convergence).
            dx, dy = x - ORIGIN_UTM[0], y - ORIGIN_UTM[1]
            e = dx * math.cos(CONVERGENCE) - dy * math.sin(CONVERGENCE)
            n = dx * math.sin(CONVERGENCE) + dy * math.cos(CONVERGENCE)
            pond = (e - 900.0) ** 2 + (n + 700.0) ** 2 < 120.0 ** 2
            row.append("-9999" if pond else f"{height(e, n):.2f}")
        lines.append(" ".join(row))
    with open(os.path.join(HERE, "real_corridor_dem.asc"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(HERE, "real_corridor_dem.prj"), "w") as f:
        f.write('PROJCS["WGS 84 / UTM zone 32N",GEOGCS["WGS 84",DATUM["WGS_1984",'
                'SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],'
                'UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],'
                'PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",9],'
                'PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],'
                'PARAMETER["false_northing",0],UNIT["metre",1]]\n')


def write_lines():
    hv = [lon_lat(e, 0.0) for e in (-1000, -600, -200, 200, 600, 1000)]
    mv = [lon_lat(e, 60.0) for e in range(-1000, 1001, 250)]
    features = [
        {"type": "Feature", "properties": {"name": "hv", "layout": "sept", "diameter_mm": 21},
         "geometry": {"type": "LineString", "coordinates": hv}},
        {"type": "Feature",
         "properties": {"name": "mv", "layout": "tri", "diameter_mm": 16, "support_height_m": 12,
                        "lowest_point_m": 9, "pole_diameter_m": 0.3},
         "geometry": {"type": "LineString", "coordinates": mv}},
    ]
    with open(os.path.join(HERE, "real_corridor_lines.geojson"), "w") as f:
        json.dump({"type": "FeatureCollection", "features": features}, f, indent=1)
        f.write("\n")


def write_barn():
    """A 24 m × 12 m barn, 8 m walls, a ridge along x at 13 m; quads and gable triangles."""
    hx, hy, wall, ridge = 12.0, 6.0, 8.0, 13.0
    vertices = [(-hx, -hy, 0), (hx, -hy, 0), (hx, hy, 0), (-hx, hy, 0),
                (-hx, -hy, wall), (hx, -hy, wall), (hx, hy, wall), (-hx, hy, wall),
                (-hx, 0, ridge), (hx, 0, ridge)]
    faces = [(1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8),   # walls
             (5, 6, 10, 9), (7, 8, 9, 10),                              # roof
             (6, 7, 10), (8, 5, 9)]                                     # gables
    lines = ["# owsim example: a gabled barn, metres, z up (examples/data/make_real_corridor.py)"]
    lines += [f"v {x:g} {y:g} {z:g}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(i) for i in face) for face in faces]
    with open(os.path.join(HERE, "real_corridor_barn.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    write_dem()
    write_lines()
    write_barn()
