// libowsim_gdal.so: the one place owsim touches GDAL. Loaded on demand by
// io/scenario/dem_terrain.cpp when a scenario's terrain is a DEM and by io/scenario/gis_lines.cpp
// when it reads power lines from GIS files, so that the owsim executable, libowsim_c.so and the
// Python module never map GDAL and the library tree behind it. The entry points are plain C: no
// exception crosses them.
//
// Posts are the raster's cell centres (GDAL's convention for both AREA and POINT rasters: the
// geotransform maps pixel (col + 0.5, row + 0.5) to the centre of cell (col, row)). Their
// coordinates in the file's CRS, with the cell's value as the vertical coordinate, are
// transformed by GDAL/PROJ to WGS-84 longitude, latitude and ellipsoidal height (EPSG:4979):
// a file whose CRS has a vertical datum (EGM96 heights, say; Debian's proj-data holds the EGM96
// grid) is converted where PROJ has the grid, and refused with PROJ's reason where it does not
// (no ballpark transformations); a file with a horizontal CRS only has its values taken as
// ellipsoidal heights (PROJ passes them through).
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/scenario/gdal_module_abi.hpp"

namespace {

void copy_error(const std::string& message, char* error, std::size_t error_size) {
  if (error == nullptr || error_size == 0) return;
  std::snprintf(error, error_size, "%s", message.c_str());
}

std::string gdal_reason() {
  const char* message = CPLGetLastErrorMsg();
  return message != nullptr && *message != '\0' ? std::string(": ") + message : std::string();
}

// Every failure GDAL reported during the current entry point (guarded() installs the handler with
// the list as its user data), also those it resets afterwards (a CRS it could not read, after
// which it falls back to a default). Not a thread_local: this is a dlopen'ed module, whose
// dynamic TLS LeakSanitizer's tracer crashes on.
using Failures = std::vector<std::string>;

struct DatasetCloser {
  void operator()(void* dataset) const { GDALClose(dataset); }
};
struct SrsReleaser {
  void operator()(void* srs) const { OSRDestroySpatialReference(srs); }
};
struct TransformReleaser {
  void operator()(void* transform) const { OCTDestroyCoordinateTransformation(transform); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;
using Srs = std::unique_ptr<void, SrsReleaser>;
using Transform = std::unique_ptr<void, TransformReleaser>;

// The posts' window: columns [col0, col0 + ncols), rows [row0, row0 + nrows).
struct Window {
  int col0 = 0, row0 = 0, ncols = 0, nrows = 0;
};

Window window_of(const double gt[6], int width, int height, OGRCoordinateTransformationH from_wgs,
                 double lon_min, double lat_min, double lon_max, double lat_max) {
  double x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  if (!OCTTransformBounds(from_wgs, lon_min, lat_min, lon_max, lat_max, &x_min, &y_min, &x_max,
                          &y_max, 21)) {
    throw std::runtime_error("cannot transform the flight's area into the file's CRS" +
                             gdal_reason());
  }
  // Fractional post indices (post k's centre is at pixel k + 0.5).
  const double c_a = (x_min - gt[0]) / gt[1] - 0.5, c_b = (x_max - gt[0]) / gt[1] - 0.5;
  const double r_a = (y_min - gt[3]) / gt[5] - 0.5, r_b = (y_max - gt[3]) / gt[5] - 0.5;
  const double c_lo = std::floor(std::min(c_a, c_b)) - 1, c_hi = std::ceil(std::max(c_a, c_b)) + 1;
  const double r_lo = std::floor(std::min(r_a, r_b)) - 1, r_hi = std::ceil(std::max(r_a, r_b)) + 1;
  Window window;
  window.col0 = static_cast<int>(std::clamp(c_lo, 0.0, width - 1.0));
  window.row0 = static_cast<int>(std::clamp(r_lo, 0.0, height - 1.0));
  const int col1 = static_cast<int>(std::clamp(c_hi, 0.0, width - 1.0));
  const int row1 = static_cast<int>(std::clamp(r_hi, 0.0, height - 1.0));
  if (c_hi < 0 || r_hi < 0 || c_lo > width - 1 || r_lo > height - 1 || col1 <= window.col0 ||
      row1 <= window.row0) {
    throw std::runtime_error("does not cover the flight's area (lon " + std::to_string(lon_min) +
                             " to " + std::to_string(lon_max) + ", lat " + std::to_string(lat_min) +
                             " to " + std::to_string(lat_max) + ")");
  }
  window.ncols = col1 - window.col0 + 1;
  window.nrows = row1 - window.row0 + 1;
  return window;
}

// The drivers a scenario's files are opened with (issue 33): formats that hold their data in the
// file itself (and sidecars beside it), never a VRT (it names other files, anywhere), an in-memory
// dataset (MEM: reads any address) or a network service (WMS, WCS, …).
const char* const kDemDrivers[] = {"GTiff",   "AAIGrid", "EHdr", "SRTMHGT",
                                   "USGSDEM", "XYZ",     "HFA",  nullptr};
const char* const kLineDrivers[] = {"GeoJSON",    "GeoJSONSeq", "ESRI Shapefile", "GPKG",
                                    "FlatGeobuf", "KML",        nullptr};

std::string driver_list(const char* const* drivers) {
  std::string list;
  for (const char* const* driver = drivers; *driver != nullptr; ++driver) {
    if (!list.empty()) list += ", ";
    list += *driver;
  }
  return list;
}

// Opens `path` with one of `drivers` only; a file another driver would read is refused by name.
Dataset open_confined(const char* path, unsigned kind, const char* const* drivers,
                      const char* what) {
  Dataset dataset(GDALOpenEx(path, kind | GDAL_OF_READONLY, drivers, nullptr, nullptr));
  if (dataset) return dataset;
  const std::string reason = gdal_reason();
  if (GDALDriverH other = GDALIdentifyDriverEx(path, kind, nullptr, nullptr)) {
    throw std::runtime_error(std::string("a ") + GDALGetDriverShortName(other) + " file, which " +
                             what + " does not accept (it reads " + driver_list(drivers) + ")");
  }
  throw std::runtime_error("GDAL cannot open it as " + driver_list(drivers) + reason);
}

// The kind of a CRS, in words.
std::string crs_kind(OGRSpatialReferenceH crs) {
  if (OSRIsCompound(crs)) return "compound";
  if (OSRIsProjected(crs)) return "projected";
  if (OSRIsGeocentric(crs)) return "geocentric";
  if (OSRIsGeographic(crs)) return "geographic";
  if (OSRIsVertical(crs)) return "vertical";
  return "other";
}

// A CRS that carries the EPSG code of another kind of CRS (a GeoTIFF's geographic keys under a
// geocentric CRS's code, found by fuzzing): PROJ looks the code up while it chooses a
// transformation and crashes on what it finds (PROJ 9.1). Refused by name before that. A code
// PROJ does not know is left to the transformation, which fails cleanly.
void require_code_of_its_kind(OGRSpatialReferenceH crs) {
  const char* authority = OSRGetAuthorityName(crs, nullptr);
  const char* code = OSRGetAuthorityCode(crs, nullptr);
  if (authority == nullptr || code == nullptr || !EQUAL(authority, "EPSG")) return;
  char* end = nullptr;
  const long number = std::strtol(code, &end, 10);
  if (end == code || *end != '\0' || number <= 0 || number > 999999) {
    throw std::runtime_error("declares a CRS with EPSG code '" + std::string(code) +
                             "', which is not an EPSG code");
  }
  const Srs by_code(OSRNewSpatialReference(nullptr));
  if (OSRImportFromEPSG(by_code.get(), static_cast<int>(number)) != OGRERR_NONE) return;
  if (crs_kind(crs) != crs_kind(by_code.get())) {
    throw std::runtime_error("declares a " + crs_kind(crs) + " CRS under EPSG:" + code +
                             ", the code of a " + crs_kind(by_code.get()) + " CRS");
  }
}

void read_dem(const char* path, bool whole_file, double lon_min, double lat_min, double lon_max,
              double lat_max, owsim_dem_begin begin, owsim_dem_rows rows, void* sink_context) {
  GDALAllRegister();
  CPLErrorReset();
  const Dataset dataset = open_confined(path, GDAL_OF_RASTER, kDemDrivers, "terrain.dem");
  if (GDALGetRasterCount(dataset.get()) < 1) throw std::runtime_error("has no raster band");
  double gt[6];
  if (GDALGetGeoTransform(dataset.get(), gt) != CE_None) {
    throw std::runtime_error("has no georeferencing (geotransform)");
  }
  if (gt[2] != 0.0 || gt[4] != 0.0 || gt[1] == 0.0 || gt[5] == 0.0) {
    throw std::runtime_error("is a rotated or sheared raster, which owsim does not read");
  }
  OGRSpatialReferenceH declared = GDALGetSpatialRef(dataset.get());
  if (declared == nullptr) throw std::runtime_error("declares no CRS");
  require_code_of_its_kind(declared);
  const Srs source(OSRClone(declared));
  OSRSetAxisMappingStrategy(source.get(), OAMS_TRADITIONAL_GIS_ORDER);
  const Srs wgs84(OSRNewSpatialReference(nullptr));
  OSRImportFromEPSG(wgs84.get(), 4979);
  OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);
  // No ballpark transformation: a vertical datum whose grid PROJ lacks is refused, not ignored.
  OGRCoordinateTransformationOptionsH options = OCTNewCoordinateTransformationOptions();
  OCTCoordinateTransformationOptionsSetBallparkAllowed(options, FALSE);
  const Transform to_wgs(OCTNewCoordinateTransformationEx(source.get(), wgs84.get(), options));
  OCTDestroyCoordinateTransformationOptions(options);
  if (!to_wgs) {
    throw std::runtime_error(
        "GDAL/PROJ cannot transform its CRS to WGS-84 exactly (a vertical "
        "datum's grid missing?)" +
        gdal_reason());
  }
  const int width = GDALGetRasterXSize(dataset.get()), height = GDALGetRasterYSize(dataset.get());
  Window window{0, 0, width, height};
  if (!whole_file) {
    // The chosen transformation run backwards: PROJ searches its database once, not twice
    // (each search is ~10 ms of a run's start).
    const Transform from_wgs(OCTGetInverse(to_wgs.get()));
    if (!from_wgs) {
      throw std::runtime_error("GDAL cannot transform WGS-84 to its CRS" + gdal_reason());
    }
    window = window_of(gt, width, height, from_wgs.get(), lon_min, lat_min, lon_max, lat_max);
  }
  if (window.ncols < 2 || window.nrows < 2) {
    throw std::runtime_error("has fewer than 2 × 2 posts where the flight is");
  }
  if (begin(sink_context, window.ncols, window.nrows) != 0) {
    throw std::runtime_error("refused by the reader");
  }
  GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  const double scale = GDALGetRasterScale(band, nullptr),
               offset = GDALGetRasterOffset(band, nullptr);
  // Blocks of about a million posts: the module's buffers stay small whatever the lattice.
  const int block_rows = std::max(1, 1'000'000 / window.ncols);
  for (int row0 = 0; row0 < window.nrows; row0 += block_rows) {
    const int nrows = std::min(block_rows, window.nrows - row0);
    const auto count = static_cast<std::size_t>(window.ncols) * static_cast<std::size_t>(nrows);
    std::vector<double> values(count);
    if (GDALRasterIO(band, GF_Read, window.col0, window.row0 + row0, window.ncols, nrows,
                     values.data(), window.ncols, nrows, GDT_Float64, 0, 0) != CE_None) {
      throw std::runtime_error("GDAL cannot read its heights" + gdal_reason());
    }
    std::vector<double> x(count), y(count), z(count);
    std::vector<unsigned char> valid(count);
    for (int r = 0; r < nrows; ++r) {
      for (int c = 0; c < window.ncols; ++c) {
        const auto i = static_cast<std::size_t>(r) * window.ncols + c;
        const double value = values[i];
        valid[i] = std::isfinite(value) && !(has_nodata != 0 && value == nodata) ? 1 : 0;
        x[i] = gt[0] + (window.col0 + c + 0.5) * gt[1];
        y[i] = gt[3] + (window.row0 + row0 + r + 0.5) * gt[5];
        z[i] = valid[i] != 0 ? value * scale + offset : 0.0;
      }
    }
    std::vector<int> success(count);
    if (!OCTTransformEx(to_wgs.get(), static_cast<int>(count), x.data(), y.data(), z.data(),
                        success.data()) ||
        std::find(success.begin(), success.end(), 0) != success.end()) {
      throw std::runtime_error("GDAL/PROJ cannot transform its posts to WGS-84" + gdal_reason());
    }
    std::vector<double> lon_lat_h(3 * count);
    for (std::size_t i = 0; i < count; ++i) {
      lon_lat_h[3 * i] = x[i];
      lon_lat_h[3 * i + 1] = y[i];
      lon_lat_h[3 * i + 2] = z[i];
    }
    rows(sink_context, row0, nrows, lon_lat_h.data(), valid.data());
  }
}

struct LayerFeatureReleaser {
  void operator()(void* feature) const { OGR_F_Destroy(feature); }
};
using Feature = std::unique_ptr<void, LayerFeatureReleaser>;

// `text` when it is UTF-8 (JSON carries nothing else); else a one-line refusal naming `what`.
std::string utf8_text(const char* text, const std::string& what) {
  std::string value = text != nullptr ? text : "";
  try {
    (void)nlohmann::json(value).dump();
  } catch (const nlohmann::json::type_error&) {
    throw std::runtime_error(what + " is not UTF-8 text");
  }
  return value;
}

nlohmann::json properties_of(OGRFeatureH feature, int index) {
  nlohmann::json properties = nlohmann::json::object();
  const std::string where = "feature " + std::to_string(index);
  for (int i = 0; i < OGR_F_GetFieldCount(feature); ++i) {
    if (!OGR_F_IsFieldSetAndNotNull(feature, i)) continue;
    OGRFieldDefnH field = OGR_F_GetFieldDefnRef(feature, i);
    const std::string name = utf8_text(OGR_Fld_GetNameRef(field), where + ": a property's name");
    switch (OGR_Fld_GetType(field)) {
      case OFTInteger:
      case OFTInteger64:
        properties[name] = OGR_F_GetFieldAsInteger64(feature, i);
        break;
      case OFTReal:
        properties[name] = OGR_F_GetFieldAsDouble(feature, i);
        break;
      default:
        properties[name] =
            utf8_text(OGR_F_GetFieldAsString(feature, i), where + ": property '" + name + "'");
    }
  }
  return properties;
}

// Every LineString in `geometry` (itself, or the parts of a multi-geometry or collection).
void collect_lines(OGRGeometryH geometry, std::vector<OGRGeometryH>& lines) {
  const OGRwkbGeometryType type = wkbFlatten(OGR_G_GetGeometryType(geometry));
  if (type == wkbLineString) {
    lines.push_back(geometry);
  } else if (type == wkbMultiLineString || type == wkbGeometryCollection) {
    for (int i = 0; i < OGR_G_GetGeometryCount(geometry); ++i) {
      collect_lines(OGR_G_GetGeometryRef(geometry, i), lines);
    }
  }
}

// GeoJSON may write a NUL character as \u0000 inside a string; GDAL hands strings over as C
// strings, so a name holding one would arrive cut short, silently. Such a file is refused.
void refuse_escaped_nul(const char* path, GDALDatasetH dataset) {
  const char* driver = GDALGetDriverShortName(GDALGetDatasetDriver(dataset));
  if (std::strcmp(driver, "GeoJSON") != 0 && std::strcmp(driver, "GeoJSONSeq") != 0) return;
  std::ifstream file(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  for (std::size_t at = text.find("\\u"); at != std::string::npos; at = text.find("\\u", at + 1)) {
    // After an escaped backslash (\\u0000 in the file) it is text, not an escape.
    std::size_t backslashes = 0;
    while (at > backslashes && text[at - backslashes - 1] == '\\') ++backslashes;
    if (backslashes % 2 == 0 && text.compare(at + 2, 4, "0000") == 0) {
      throw std::runtime_error(
          "holds a text value with a NUL character (\\u0000), which GDAL would cut short");
    }
  }
}

void read_lines(const char* path, owsim_line_sink sink, void* sink_context,
                const Failures& failures) {
  GDALAllRegister();
  CPLErrorReset();
  const Dataset dataset = open_confined(path, GDAL_OF_VECTOR, kLineDrivers, "power_lines");
  refuse_escaped_nul(path, dataset.get());
  const Srs wgs84(OSRNewSpatialReference(nullptr));
  OSRImportFromEPSG(wgs84.get(), 4326);
  OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);
  int emitted = 0;
  std::size_t towers = 0;
  for (int l = 0; l < GDALDatasetGetLayerCount(dataset.get()); ++l) {
    OGRLayerH layer = GDALDatasetGetLayer(dataset.get(), l);
    OGRSpatialReferenceH declared = OGR_L_GetSpatialRef(layer);
    // A CRS GDAL failed to read (GeoJSON's crs member naming one PROJ does not know) leaves the
    // layer in GDAL's default, WGS-84, after a failure it reported: refused, not guessed.
    for (const std::string& failure : failures) {
      if (failure.find("crs") != std::string::npos || failure.find("CRS") != std::string::npos) {
        throw std::runtime_error("layer " + std::to_string(l) +
                                 ": its CRS cannot be read: " + failure);
      }
    }
    // GeoJSON without a crs member is WGS-84 (GDAL says so); a CRS GDAL cannot read, or a format
    // that declares none (a shapefile without .prj), is refused rather than guessed.
    if (declared == nullptr) {
      throw std::runtime_error("layer " + std::to_string(l) +
                               " declares no CRS that GDAL can read (GeoJSON: leave out the crs "
                               "member for WGS-84)" +
                               gdal_reason());
    }
    Transform to_wgs;
    {
      require_code_of_its_kind(declared);
      const Srs source(OSRClone(declared));
      OSRSetAxisMappingStrategy(source.get(), OAMS_TRADITIONAL_GIS_ORDER);
      to_wgs.reset(OCTNewCoordinateTransformation(source.get(), wgs84.get()));
      if (!to_wgs) {
        throw std::runtime_error("GDAL cannot transform its CRS to WGS-84" + gdal_reason());
      }
    }
    OGR_L_ResetReading(layer);
    for (int index = 0;; ++index) {
      const Feature feature(OGR_L_GetNextFeature(layer));
      if (!feature) break;
      OGRGeometryH geometry = OGR_F_GetGeometryRef(feature.get());
      if (geometry == nullptr) continue;
      if (to_wgs && OGR_G_Transform(geometry, to_wgs.get()) != OGRERR_NONE) {
        throw std::runtime_error("cannot transform feature " + std::to_string(index) +
                                 " to WGS-84" + gdal_reason());
      }
      std::vector<OGRGeometryH> lines;
      collect_lines(geometry, lines);
      const nlohmann::json properties = properties_of(feature.get(), index);
      for (OGRGeometryH line : lines) {
        towers += static_cast<std::size_t>(std::max(0, OGR_G_GetPointCount(line)));
        if (towers > OWSIM_MAX_GIS_TOWERS) {
          throw std::runtime_error("holds more than " + std::to_string(OWSIM_MAX_GIS_TOWERS) +
                                   " towers (line vertices), the most owsim builds from one file; "
                                   "cut it to the flight's area");
        }
        nlohmann::json coordinates = nlohmann::json::array();
        for (int p = 0; p < OGR_G_GetPointCount(line); ++p) {
          coordinates.push_back({OGR_G_GetX(line, p), OGR_G_GetY(line, p)});
        }
        const nlohmann::json out = {
            {"feature", index}, {"properties", properties}, {"coordinates", coordinates}};
        sink(sink_context, out.dump().c_str());
        ++emitted;
      }
    }
  }
  if (emitted == 0) throw std::runtime_error("holds no LineString");
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int owsim_gdal_module_abi(void) {
  return OWSIM_GDAL_MODULE_ABI;
}

void CPL_STDCALL keep_failures(CPLErr level, CPLErrorNum, const char* message) {
  auto* failures = static_cast<Failures*>(CPLGetErrorHandlerUserData());
  if (level >= CE_Failure && failures != nullptr) {
    failures->emplace_back(message != nullptr ? message : "");
  }
}

// Runs `body(failures)`, turning any exception into status 1 and a one-line message: nothing
// crosses the C boundary.
template <typename Body>
int guarded(char* error, std::size_t error_size, const Body& body) {
  Failures failures;
  CPLPushErrorHandlerEx(keep_failures, &failures);
  int status = 0;
  try {
    body(failures);
  } catch (const std::exception& failure) {
    copy_error(failure.what(), error, error_size);
    status = 1;
  } catch (...) {
    copy_error("an unknown error in the GDAL module", error, error_size);
    status = 1;
  }
  CPLPopErrorHandler();
  return status;
}

extern "C" __attribute__((visibility("default"))) int owsim_dem_read(
    const char* path, int whole_file, double lon_min, double lat_min, double lon_max,
    double lat_max, owsim_dem_begin begin, owsim_dem_rows rows, void* sink_context, char* error,
    std::size_t error_size) {
  return guarded(error, error_size, [&](const Failures&) {
    read_dem(path, whole_file != 0, lon_min, lat_min, lon_max, lat_max, begin, rows, sink_context);
  });
}

extern "C" __attribute__((visibility("default"))) int owsim_dataset_files(
    const char* path, int vector, owsim_file_sink sink, void* sink_context, char* error,
    std::size_t error_size) {
  return guarded(error, error_size, [&](const Failures&) {
    GDALAllRegister();
    CPLErrorReset();
    const Dataset dataset = vector != 0
                                ? open_confined(path, GDAL_OF_VECTOR, kLineDrivers, "power_lines")
                                : open_confined(path, GDAL_OF_RASTER, kDemDrivers, "terrain.dem");
    char** files = GDALGetFileList(dataset.get());
    for (char** file = files; file != nullptr && *file != nullptr; ++file)
      sink(sink_context, *file);
    CSLDestroy(files);
  });
}

extern "C" __attribute__((visibility("default"))) int owsim_lines_read(const char* path,
                                                                       owsim_line_sink sink,
                                                                       void* sink_context,
                                                                       char* error,
                                                                       std::size_t error_size) {
  return guarded(error, error_size,
                 [&](const Failures& failures) { read_lines(path, sink, sink_context, failures); });
}
