#pragma once
// Lines from GIS vector files (scenario key power_lines, ../shared/INTERFACE.md "Real-world
// scenes"): every LineString of a GeoJSON file, or of any vector format GDAL/OGR reads, in WGS-84,
// with its feature's properties; read through the optional module libowsim_gdal.so.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

namespace owsim {

struct GisLine {
  int feature = 0;                       // the feature's index in its layer
  nlohmann::json properties;             // the feature's fields: numbers and strings
  std::vector<Eigen::Vector2d> lon_lat;  // vertices, WGS-84 degrees (longitude, latitude)
};

// Throws owsim::Error "<file>: <problem>" (the module missing, a file OGR cannot open, a CRS it
// cannot transform, no LineString in it).
[[nodiscard]] std::vector<GisLine> read_gis_lines(const std::filesystem::path& file);

}  // namespace owsim
