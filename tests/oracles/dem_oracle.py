"""Independent checks of DEM terrain (io/scenario/dem_terrain.hpp) with GDAL's Python bindings.

    dem_oracle.py make DIR LAT LON      writes DIR/utm.tif (projected, the origin's UTM zone, 10 m
                                        cells), DIR/geo.tif (EPSG:4326, 0.0001° cells), each with a
                                        NODATA patch, DIR/egm96.tif (utm.tif's values as EGM96
                                        heights: UTM + EPSG:5773) and DIR/nocrs.tif (no CRS),
                                        around LAT, LON
    dem_oracle.py check POINTS RASTER   every ground return of POINTS (points.csv) against the
                                        raster's own bilinear interpolation at its latitude and
                                        longitude (GDAL's transform to the raster's CRS), turned
                                        into an ellipsoidal height by GDAL/PROJ; prints
                                        "ok <ground returns> <largest |Δh| in mm>" or fails

The surface owsim traces is two planar triangles per cell between the posts; bilinear
interpolation differs from it by at most a quarter of the cell's twist |h00 + h11 − h01 − h10|,
so each return's bound is that plus 2 mm (float rounding of the traced ray, the reprojection).
Heights are ellipsoidal where a raster declares no vertical datum; EGM96 heights are converted
with PROJ's geoid grid (Debian's proj-data).
"""
import csv
import math
import sys

from osgeo import gdal, osr

gdal.UseExceptions()


def height_model(east_m, north_m):
    """A smooth landscape, metres above the ellipsoid, from offsets to the centre."""
    return (450.0 + 25.0 * math.sin(east_m / 310.0) + 12.0 * math.cos(north_m / 190.0)
            + 0.00002 * east_m * north_m)


def write(path, srs, origin_x, origin_y, step_x, step_y, width, height, value_at, hole):
    driver = gdal.GetDriverByName("GTiff")
    dataset = driver.Create(path, width, height, 1, gdal.GDT_Float32)
    dataset.SetGeoTransform([origin_x, step_x, 0.0, origin_y, 0.0, step_y])
    if srs is not None:
        dataset.SetProjection(srs.ExportToWkt())
    band = dataset.GetRasterBand(1)
    band.SetNoDataValue(-9999.0)
    rows = []
    for r in range(height):
        row = []
        for c in range(width):
            x = origin_x + (c + 0.5) * step_x
            y = origin_y + (r + 0.5) * step_y
            row.append(-9999.0 if hole(r, c) else value_at(x, y))
        rows.append(row)
    import numpy
    band.WriteArray(numpy.array(rows, dtype=numpy.float32))
    dataset.FlushCache()
    dataset = None


def make(folder, lat, lon):
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4326)
    wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    zone = int((lon + 180.0) // 6) + 1
    utm = osr.SpatialReference()
    utm.ImportFromEPSG(32600 + zone if lat >= 0 else 32700 + zone)
    utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to_utm = osr.CoordinateTransformation(wgs84, utm)
    cx, cy, _ = to_utm.TransformPoint(lon, lat)
    half = 2500.0
    cells = int(2 * half / 10.0)
    # A NODATA patch far south-east of the centre, away from the test's flight.
    hole = lambda r, c: 420 <= r < 440 and 420 <= c < 440
    write(f"{folder}/utm.tif", utm, cx - half, cy + half, 10.0, -10.0, cells, cells,
          lambda x, y: height_model(x - cx, y - cy), hole)
    compound = osr.SpatialReference()
    compound.SetFromUserInput(f"EPSG:{32600 + zone}+5773")
    compound.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    write(f"{folder}/egm96.tif", compound, cx - half, cy + half, 10.0, -10.0, cells, cells,
          lambda x, y: height_model(x - cx, y - cy) - 47.0, hole)
    write(f"{folder}/nocrs.tif", None, cx - half, cy + half, 10.0, -10.0, 20, 20,
          lambda x, y: 450.0, lambda r, c: False)
    step = 0.0001
    half_lat, half_lon = 0.02, 0.03
    per_deg_n = 111_200.0
    per_deg_e = per_deg_n * math.cos(math.radians(lat))
    write(f"{folder}/geo.tif", wgs84, lon - half_lon, lat + half_lat, step, -step,
          int(2 * half_lon / step), int(2 * half_lat / step),
          lambda x, y: height_model((x - lon) * per_deg_e, (y - lat) * per_deg_n),
          lambda r, c: 250 <= r < 270 and 300 <= c < 330)


def transforms(dataset):
    """WGS-84 → the raster's CRS (2-D), and the raster's CRS → WGS-84 ellipsoidal (3-D)."""
    srs = dataset.GetSpatialRef()
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4979)
    wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return osr.CoordinateTransformation(wgs84, srs), osr.CoordinateTransformation(srs, wgs84)


def bilinear(dataset, to_raster, to_wgs84, lat, lon):
    """GDAL's own bilinear interpolation at (lat, lon) as an ellipsoidal height, and the cell's
    twist bound."""
    x, y, _ = to_raster.TransformPoint(lon, lat, 0.0)
    gt = dataset.GetGeoTransform()
    col = (x - gt[0]) / gt[1] - 0.5
    row = (y - gt[3]) / gt[5] - 0.5
    c0, r0 = int(math.floor(col)), int(math.floor(row))
    band = dataset.GetRasterBand(1)
    window = band.ReadAsArray(c0, r0, 2, 2).astype(float)
    # GDAL's bilinear resampling of that 2 × 2 window to the point.
    sample = gdal.Translate("", dataset, format="MEM", width=1, height=1, resampleAlg="bilinear",
                            srcWin=[col + 0.5 - 0.5, row + 0.5 - 0.5, 1, 1])
    value = float(sample.GetRasterBand(1).ReadAsArray()[0][0])
    fc, fr = col - c0, row - r0
    by_hand = ((1 - fr) * ((1 - fc) * window[0][0] + fc * window[0][1])
               + fr * ((1 - fc) * window[1][0] + fc * window[1][1]))
    if abs(value - by_hand) > 1e-3:
        sys.exit(f"GDAL's bilinear {value} and the formula's {by_hand} disagree at {lat}, {lon}")
    twist = abs(window[0][0] + window[1][1] - window[0][1] - window[1][0])
    # The raster's height at that point, as a WGS-84 ellipsoidal height.
    _, _, h = to_wgs84.TransformPoint(x, y, value)
    return h, twist / 4.0


def check(points_path, raster_path):
    dataset = gdal.Open(raster_path)
    to_raster, to_wgs84 = transforms(dataset)
    count, worst = 0, 0.0
    with open(points_path, newline="") as f:
        for row in csv.DictReader(f):
            if row["class"] != "ground":
                continue
            lat, lon, h = float(row["lat_deg"]), float(row["lon_deg"]), float(row["h_m"])
            expected, bound = bilinear(dataset, to_raster, to_wgs84, lat, lon)
            error = abs(h - expected)
            if error > bound + 0.002:
                sys.exit(f"ground return at {lat}, {lon}: h {h} vs bilinear {expected} "
                         f"(bound {bound + 0.002} m)")
            worst = max(worst, error)
            count += 1
    print(f"ok {count} {worst * 1000.0:.3f}")


if __name__ == "__main__":
    if sys.argv[1] == "make":
        make(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
    else:
        check(sys.argv[2], sys.argv[3])
