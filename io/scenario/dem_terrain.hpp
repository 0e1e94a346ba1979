#pragma once
// A DEM raster as terrain (scenario key terrain.dem, ../shared/INTERFACE.md "Real-world scenes"):
// read through the optional module libowsim_gdal.so (GDAL: the raster formats it lists, any CRS),
// each post reprojected to WGS-84 by GDAL/PROJ and placed in the local ENU frame by GeographicLib
// (LocalCartesian), so the lattice is exact wherever it lies; the surface between posts is
// geometry/post_lattice.hpp's triangles.
//
// Only the posts within `reach` (local east/north metres; the flight's area widened by the
// counter's timeout range) and one post around are read, so a country-sized DEM costs memory
// for the corridor only. Without a reach (nullopt) the whole raster is read.
#include <Eigen/Geometry>
#include <filesystem>
#include <optional>

#include "geometry/geodetic_frame.hpp"
#include "geometry/post_lattice.hpp"

namespace owsim {

// The memory a post in reach costs while a flight runs (measured, docs/scenario.md "Terrain from
// a DEM"): the lattice in double (25 bytes), Embree's float copy and grid BVH. A DEM whose posts
// in reach would need more than the machine's physical memory is refused before it is read.
inline constexpr int kDemBytesPerPost = 64;

// Throws owsim::Error with one line naming the file and the problem (the module missing, a file
// GDAL cannot open, a CRS it cannot transform, a DEM that does not cover the reach, fewer than
// 2 × 2 posts there, more posts than fit in memory).
[[nodiscard]] PostLattice read_dem_terrain(const std::filesystem::path& file,
                                           const LocalFrame& frame,
                                           const std::optional<Eigen::AlignedBox2d>& reach);

}  // namespace owsim
