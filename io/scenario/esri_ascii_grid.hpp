#pragma once
// Reader for ESRI ASCII grids (.asc) — the terrain file of a scenario (INTERFACE.md
// scene.terrain.grid), in the local ENU frame.
//
// Format: header lines "key value" with the keys ncols, nrows, xllcorner or xllcenter,
// yllcorner or yllcenter, cellsize, and optionally NODATA_value (keys case-insensitive, any
// order), then nrows × ncols numbers separated by any whitespace, the north row first. A
// corner origin is moved half a cell east and north to the centre of the south-west cell
// (HeightGrid's convention). Every problem throws owsim::Error "<path>:<line>: <problem>":
// an unreadable file, an unknown, repeated or missing key (reported at the line where the data
// begin), a bad header value (ncols/nrows not an integer ≥ 2, cellsize not > 0), a value that is
// not a finite number, too few values (at the last line) or too many.
#include <string>

#include "geometry/height_grid.hpp"

namespace owsim {

[[nodiscard]] HeightGrid read_esri_ascii_grid(const std::string& path);

}  // namespace owsim
