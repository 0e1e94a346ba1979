#pragma once
// The optional module libowsim_gdal.so (io/scenario/gdal/gdal_module.cpp): GDAL for DEM terrain
// and GIS power lines, loaded on the first scenario that needs it.
#include <filesystem>
#include <string_view>
#include <vector>

#include "io/files/optional_module.hpp"

namespace owsim {

// The loaded module, its interface version checked. Throws owsim::Error with one line naming
// what needs it (`purpose`) when it cannot be loaded or is of another interface.
[[nodiscard]] const OptionalModule& gdal_module(std::string_view purpose);

// The files of the dataset `file` other than itself (a shapefile's .dbf, a raster's sidecars),
// as GDAL opens it for terrain.dem (vector false) or power_lines (true). Throws owsim::Error
// "<file>: <problem>".
[[nodiscard]] std::vector<std::filesystem::path> dataset_companions(
    const std::filesystem::path& file, bool vector);

}  // namespace owsim
