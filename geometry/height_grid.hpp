#pragma once
// A regular grid of terrain heights in the local ENU frame (the content of an ESRI ASCII grid,
// io/scenario/esri_ascii_grid.hpp), read as a lattice of height samples at the cell centres.
//
// Sample (row, col) stands at e = x_west_m + col·cellsize_m, n = y_south_m + (nrows − 1 − row)·
// cellsize_m: x_west_m / y_south_m are the centre of the south-west cell (an ESRI "xllcenter";
// a file's "xllcorner" is half a cell further west). Rows are stored north row first, as in the
// file. The terrain exists on the lattice's extent, between the outer sample centres; there it is
// the bilinear interpolation of the four surrounding samples, exact to rounding.
// Valid: ncols, nrows ≥ 2, cellsize_m > 0, heights.size() = ncols·nrows, finite values except
// the NODATA marker.
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

namespace owsim {

struct HeightGrid {
  int ncols = 0;
  int nrows = 0;
  double x_west_m = 0.0;   // east coordinate of the westmost sample column (cell centres)
  double y_south_m = 0.0;  // north coordinate of the southmost sample row (cell centres)
  double cellsize_m = 1.0;
  std::vector<double> heights;   // row-major, north row first: heights[row·ncols + col]
  std::optional<double> nodata;  // the marker of a missing sample, if the grid has one

  [[nodiscard]] double sample(int row, int col) const {
    return heights[static_cast<std::size_t>(row) * static_cast<std::size_t>(ncols) +
                   static_cast<std::size_t>(col)];
  }
  [[nodiscard]] bool is_nodata(double value) const { return nodata && value == *nodata; }
  [[nodiscard]] double east_of_col_m(int col) const { return x_west_m + col * cellsize_m; }
  [[nodiscard]] double north_of_row_m(int row) const {
    return y_south_m + (nrows - 1 - row) * cellsize_m;
  }
  [[nodiscard]] double x_east_m() const { return east_of_col_m(ncols - 1); }
  [[nodiscard]] double y_north_m() const { return north_of_row_m(0); }

  // Throws owsim::Error "<where>: …" if the grid breaks the valid range above.
  void validate(std::string_view where) const;
  // Bilinear height at (e, n). Throws owsim::Error if (e, n) lies outside the lattice extent
  // (beyond a rounding margin of 1e-9 cells) or a sample it needs is NODATA.
  [[nodiscard]] double height_at(double e_m, double n_m) const;
};

}  // namespace owsim
