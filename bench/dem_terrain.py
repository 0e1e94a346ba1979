"""What DEM terrain costs, measured in one sitting (issue 20):

1. per pulse: `owsim bench` on the corridor (examples/corridor.yaml) over its flat ground and over
   DEMs of rolling hills (10 m and 30 m cells, UTM 32N GeoTIFFs), the same objects and flight;
   trace-only and end-to-end pulses/s of each and their ratio to flat; and the example
   examples/real_corridor.yaml (the corridor from GIS data over a 40 m DEM) against the flat
   corridor;
2. memory against the file: the same flight (`owsim run --frames 30 --outputs d64,summary`) over
   DEMs of growing extent, from the flight's reach to a country-sized raster; peak RSS (the child's
   own ru_maxrss), set-up time (summary.json's setup_s) and the file's size. Only the posts within
   the flight's reach are read, so the peak should not follow the file;
3. memory against the posts in reach (issue 33): a 1 s flight 60 m up (reach 2.5 × 2.5 km) over
   3 × 3 km DEMs of 4, 2 and 1 m cells; peak RSS and the bytes each post in reach costs, from the
   difference between 1 m and 2 m (both above a million posts: grid primitives; what the loader's
   kDemBytesPerPost bounds);
4. the corridor's whole 65 s flight over a 6 × 6 km DEM of 1 m cells (36 M cells; its reach
   holds ~15 M posts): peak RSS, set-up and wall time (`--corridor-1m`, alone: the GeoTIFF takes
   a minute to write).

    /usr/bin/python3 bench/dem_terrain.py [--owsim build/owsim] [--extents-km 6,30,120]

The rasters are written by a child process (`--write PATH KM CELL_M`), so the peak RSS of each
owsim child is its own, not the inherited image of a parent that held a raster in memory.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy
from osgeo import gdal, osr

gdal.UseExceptions()
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORRIDOR = os.path.join(ROOT, "examples", "corridor.yaml")
LAT0, LON0 = 48.6881, 10.8447


def write_dem(path, extent_km, cell_m):
    """A tiled, compressed GeoTIFF of rolling hills, `extent_km` square around the origin."""
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32632)
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4326)
    wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    cx, cy, _ = osr.CoordinateTransformation(wgs84, srs).TransformPoint(LON0, LAT0)
    cells = int(extent_km * 1000.0 / cell_m)
    half = cells * cell_m / 2.0
    dataset = gdal.GetDriverByName("GTiff").Create(
        path, cells, cells, 1, gdal.GDT_Float32,
        options=["TILED=YES", "COMPRESS=DEFLATE", "PREDICTOR=3", "BIGTIFF=IF_SAFER"])
    dataset.SetGeoTransform([cx - half, cell_m, 0.0, cy + half, 0.0, -cell_m])
    dataset.SetProjection(srs.ExportToWkt())
    band = dataset.GetRasterBand(1)
    x = (numpy.arange(cells) + 0.5) * cell_m - half
    block = 512
    for r0 in range(0, cells, block):
        rows = min(block, cells - r0)
        y = half - (numpy.arange(r0, r0 + rows) + 0.5) * cell_m
        yy, xx = numpy.meshgrid(y, x, indexing="ij")
        heights = 450.0 + 14.0 * numpy.sin(xx / 380.0) * numpy.cos(yy / 290.0) + 6.0 * numpy.sin(yy / 170.0)
        band.WriteArray(heights.astype(numpy.float32), 0, r0)
    dataset.FlushCache()
    dataset = None
    return os.path.getsize(path)


def scenario_over(folder, dem):
    with open(CORRIDOR, encoding="utf-8") as f:
        text = f.read()
    flat = "terrain: {flat_u: 0, reflectivity: 0.2}"
    assert flat in text, f"{CORRIDOR} no longer holds '{flat}'"
    text = text.replace(flat, f"terrain: {{dem: {dem}, reflectivity: 0.2}}")
    text = text.replace("u: 90}", "u: 110}")  # clear of the hills
    path = os.path.join(folder, os.path.basename(dem) + ".yaml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def flat_scenario(folder):
    with open(CORRIDOR, encoding="utf-8") as f:
        text = f.read().replace("u: 90}", "u: 110}")
    path = os.path.join(folder, "flat.yaml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def bench(owsim, scenario):
    out = subprocess.run([owsim, "bench", scenario], capture_output=True, text=True, check=True)
    text = out.stdout + out.stderr
    end_to_end = float(re.search(r"end-to-end\s+(\d+) pulses/s", text).group(1))
    trace = float(re.search(r"trace-only\s+(\d+) pulses/s", text).group(1))
    return end_to_end, trace


def run(owsim, scenario, out, frames=None):
    """One `owsim run --outputs d64,summary`: its own peak RSS (MB), set-up and wall time (s), and
    the frames it flew."""
    command = [owsim, "run", scenario, "--outputs", "d64,summary", "--out", out, "--quiet"]
    if frames is not None:
        command += ["--frames", str(frames)]
    start = time.perf_counter()
    child = subprocess.Popen(command)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        sys.exit(f"owsim run {scenario} failed")
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    return usage.ru_maxrss / 1000.0, summary["setup_s"], wall, summary["frames"]


HOVER = """name: fine_dem
seed: 1
origin: {lat: 48.6881, lon: 10.8447, h: 450.0}
sensor: {model: milows}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: -20, n: 0, u: 60}, {e: 20, n: 0, u: 60}]
  start_s: 0
  duration_s: 1
scene:
  terrain: {dem: DEM}
"""
TIMEOUT_RANGE_M = 1238.36  # SENSOR-SPEC: 2066 ticks


def posts_in_reach(cell_m):
    """The posts of the reach box (the 40 m flown, widened by the timeout range), one around."""
    east = 40.0 + 2 * TIMEOUT_RANGE_M
    north = 2 * TIMEOUT_RANGE_M
    return (east / cell_m + 3) * (north / cell_m + 3)


def peak_over(owsim, folder, dem):
    path = os.path.join(folder, "hover_" + os.path.basename(dem) + ".yaml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(HOVER.replace("DEM", dem))
    peak, setup, _, _ = run(owsim, path, os.path.join(folder, "out_" + os.path.basename(dem)))
    return peak, setup


def write_in_child(path, km, cell_m):
    subprocess.run([sys.executable, os.path.abspath(__file__), "--write", path, str(km),
                    str(cell_m)], check=True)
    return os.path.getsize(path)


def main():
    if len(sys.argv) == 5 and sys.argv[1] == "--write":
        write_dem(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
        return
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--owsim", default=os.path.join(ROOT, "build", "owsim"))
    parser.add_argument("--extents-km", default="6,30,120")
    parser.add_argument("--corridor-1m", action="store_true",
                        help="only the corridor's whole flight over a 1 m DEM")
    args = parser.parse_args()
    if args.corridor_1m:
        with tempfile.TemporaryDirectory(prefix="owsim_dem_bench_") as folder:
            dem = os.path.join(folder, "corridor_1m.tif")
            size = write_in_child(dem, 6.0, 1.0)
            scenario = scenario_over(folder, dem)
            peak, setup, wall, frames = run(args.owsim, scenario, os.path.join(folder, "out"))
            print(f"corridor, whole flight ({frames} frames) over a 6 × 6 km 1 m DEM "
                  f"({size / 1e6:.0f} MB): peak {peak:.0f} MB, set-up {setup:.2f} s, "
                  f"wall {wall:.2f} s")
        return
    extents = [float(x) for x in args.extents_km.split(",")]
    with tempfile.TemporaryDirectory(prefix="owsim_dem_bench_") as folder:
        flat = flat_scenario(folder)
        flat_e2e, flat_trace = bench(args.owsim, flat)
        print("| ground | end-to-end pulses/s | trace-only pulses/s | end-to-end / flat | "
              "trace-only / flat |")
        print("|---|---|---|---|---|")
        print(f"| flat | {flat_e2e / 1e6:.2f} M | {flat_trace / 1e6:.2f} M | 1 | 1 |")
        for cell in (10.0, 30.0):
            dem = os.path.join(folder, f"cell_{cell:g}.tif")
            write_in_child(dem, extents[0], cell)
            e2e, trace = bench(args.owsim, scenario_over(folder, dem))
            print(f"| DEM {cell:g} m cells | {e2e / 1e6:.2f} M | {trace / 1e6:.2f} M | "
                  f"{e2e / flat_e2e:.2f} | {trace / flat_trace:.2f} |")
        e2e, trace = bench(args.owsim, os.path.join(ROOT, "examples", "real_corridor.yaml"))
        print(f"| real_corridor example (40 m DEM) | {e2e / 1e6:.2f} M | {trace / 1e6:.2f} M | "
              f"{e2e / flat_e2e:.2f} | {trace / flat_trace:.2f} |")
        print()
        print("| DEM extent (10 m cells) | file MB | cells | set-up s | peak MB | run wall s |")
        print("|---|---|---|---|---|---|")
        peak, setup, wall, _ = run(args.owsim, flat, os.path.join(folder, "out_flat"), frames=30)
        print(f"| flat ground | – | – | {setup:.3f} | {peak:.0f} | {wall:.2f} |")
        for km in extents:
            dem = os.path.join(folder, f"dem_{km:g}km.tif")
            size = write_in_child(dem, km, 10.0)
            scenario = scenario_over(folder, dem)
            peak, setup, wall, _ = run(args.owsim, scenario, os.path.join(folder, f"out_{km:g}"),
                                       frames=30)
            cells = int(km * 100) ** 2
            print(f"| {km:g} × {km:g} km | {size / 1e6:.0f} | {cells:,} | {setup:.3f} | "
                  f"{peak:.0f} | {wall:.2f} |")
            os.remove(dem)
        print()
        print("| cells (3 × 3 km) | posts in reach | set-up s | peak MB |")
        print("|---|---|---|---|")
        peaks = {}
        for cell in (4.0, 2.0, 1.0):
            dem = os.path.join(folder, f"fine_{cell:g}m.tif")
            write_in_child(dem, 3.0, cell)
            peak, setup = peak_over(args.owsim, folder, dem)
            peaks[cell] = peak
            print(f"| {cell:g} m | {posts_in_reach(cell) / 1e6:.1f} M | {setup:.2f} | {peak:.0f} |")
            os.remove(dem)
        per_post = (peaks[1.0] - peaks[2.0]) * 1e6 / (posts_in_reach(1.0) - posts_in_reach(2.0))
        print(f"\nbytes a post in reach (1 m against 2 m): {per_post:.0f}")


if __name__ == "__main__":
    main()
