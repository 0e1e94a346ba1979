#pragma once
// The C entry points of libowsim_gdal.so (io/scenario/gdal/gdal_module.cpp), the optional module
// that reads elevation rasters and line features with GDAL/OGR. The loader
// (io/scenario/dem_terrain.cpp) refuses a module whose owsim_gdal_module_abi() differs from
// OWSIM_GDAL_MODULE_ABI.
#include <cstddef>

#define OWSIM_GDAL_MODULE_ABI 3

extern "C" {

// Receives the size of the ncols × nrows lattice about to be read, before anything is allocated
// for it. Returns 0 to go on; non-zero stops the read (owsim_dem_read then returns non-zero and
// the caller gives its own reason).
typedef int (*owsim_dem_begin)(void* context, int ncols, int nrows);
// Receives rows [row0, row0 + nrows) of the lattice, raster row 0 first, in order: lon_lat_h
// holds 3 doubles a post (WGS-84 longitude and latitude in degrees, ellipsoidal height in metres;
// NODATA posts at height 0), valid 1 byte a post (0 = NODATA).
typedef void (*owsim_dem_rows)(void* context, int row0, int nrows, const double* lon_lat_h,
                               const unsigned char* valid);

typedef int (*owsim_gdal_module_abi_fn)(void);
// Only the drivers gdal_module.cpp lists open a file (formats that hold their data in the file and
// sidecars beside it: no VRT, no in-memory or network dataset). Reads band 1 of the raster at
// `path`: the posts (cell centres) inside the WGS-84 box
// [lon_min, lon_max] × [lat_min, lat_max] and one post around it, or every post when
// whole_file is non-zero, reprojected from the CRS the file declares to WGS-84 (EPSG:4979).
// Calls `begin` once, then `rows` for blocks of rows (so the posts are never held twice), and
// returns 0; or returns non-zero with a one-line message in `error`.
typedef int (*owsim_dem_read_fn)(const char* path, int whole_file, double lon_min, double lat_min,
                                 double lon_max, double lat_max, owsim_dem_begin begin,
                                 owsim_dem_rows rows, void* sink_context, char* error,
                                 std::size_t error_size);

// The most towers (line vertices) owsim_lines_read takes from one file: a million-tower line ran
// for 15 s into 2.8 GB before Embree failed.
#define OWSIM_MAX_GIS_TOWERS 100000u

// Receives one line of a vector file (called once per LineString, and per part of a
// MultiLineString, in the file's order) as JSON text: {"feature": index in its layer,
// "properties": {field: number or string, ...}, "coordinates": [[lon, lat], ...]} (WGS-84
// degrees).
typedef void (*owsim_line_sink)(void* context, const char* line_json);
// Reads every line of every layer of the vector file at `path` (GeoJSON, or the other formats
// gdal_module.cpp lists), reprojected from its CRS to WGS-84. Returns 0 after calling `sink` for
// each line (at least one), or non-zero with a one-line message in `error`.
typedef int (*owsim_lines_read_fn)(const char* path, owsim_line_sink sink, void* sink_context,
                                   char* error, std::size_t error_size);

// Receives one file name.
typedef void (*owsim_file_sink)(void* context, const char* path);
// The files of the dataset at `path` (GDAL's file list: the file and its sidecars — a shapefile's
// .shx, .dbf and .prj, a raster's .aux.xml or world file), opened as owsim_dem_read (vector == 0)
// or owsim_lines_read (vector != 0) would open it. Returns 0 after calling `sink` for each, or
// non-zero with a one-line message in `error`.
typedef int (*owsim_dataset_files_fn)(const char* path, int vector, owsim_file_sink sink,
                                      void* sink_context, char* error, std::size_t error_size);
}
