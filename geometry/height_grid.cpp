#include "geometry/height_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {
namespace {

constexpr double kEdgeMarginCells = 1e-9;

// Cell index and fraction of a coordinate measured in cells from the first sample, clamped to
// the lattice: index ∈ [0, count − 2], fraction ∈ [0, 1].
void locate(double cells, int count, int& index, double& fraction) {
  const double clamped = std::clamp(cells, 0.0, static_cast<double>(count - 1));
  index = std::min(static_cast<int>(std::floor(clamped)), count - 2);
  fraction = clamped - index;
}

}  // namespace

void HeightGrid::validate(std::string_view where) const {
  if (ncols < 2 || nrows < 2) {
    throw input_error(where, "a terrain grid needs at least 2 columns and 2 rows, got " +
                                 std::to_string(ncols) + " × " + std::to_string(nrows));
  }
  if (!(std::isfinite(cellsize_m) && cellsize_m > 0.0)) {
    throw input_error(where,
                      "cellsize must be a finite number > 0, got " + number_text(cellsize_m, 10));
  }
  if (!(std::isfinite(x_west_m) && std::isfinite(y_south_m))) {
    throw input_error(where, "the lower-left coordinates must be finite");
  }
  const auto expected = static_cast<std::size_t>(ncols) * static_cast<std::size_t>(nrows);
  if (heights.size() != expected) {
    throw input_error(where, "holds " + std::to_string(heights.size()) + " heights, " +
                                 std::to_string(ncols) + " × " + std::to_string(nrows) + " needs " +
                                 std::to_string(expected));
  }
  for (std::size_t i = 0; i < heights.size(); ++i) {
    if (!std::isfinite(heights[i]) && !is_nodata(heights[i])) {
      throw input_error(where, "height " + std::to_string(i) + " is not finite");
    }
  }
}

double HeightGrid::height_at(double e_m, double n_m) const {
  const double col_cells = (e_m - x_west_m) / cellsize_m;
  const double row_cells = (n_m - y_south_m) / cellsize_m;  // from the south row
  const double margin = kEdgeMarginCells;
  if (!(col_cells >= -margin && col_cells <= ncols - 1 + margin && row_cells >= -margin &&
        row_cells <= nrows - 1 + margin)) {
    throw Error("terrain grid: point (e " + number_text(e_m, 10) + ", n " + number_text(n_m, 10) +
                ") lies outside the grid, which covers e " + number_text(x_west_m, 10) + ".." +
                number_text(x_east_m(), 10) + ", n " + number_text(y_south_m, 10) + ".." +
                number_text(y_north_m(), 10));
  }
  int col = 0, south_row = 0;
  double fx = 0.0, fy = 0.0;
  locate(col_cells, ncols, col, fx);
  locate(row_cells, nrows, south_row, fy);
  const int row = nrows - 1 - south_row;  // storage row of the southern pair, north row first
  const double corner_weights[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const int corner_rows[4] = {row, row, row - 1, row - 1};
  const int corner_cols[4] = {col, col + 1, col, col + 1};
  double height = 0.0;
  for (int k = 0; k < 4; ++k) {
    if (corner_weights[k] == 0.0) continue;
    const double value = sample(corner_rows[k], corner_cols[k]);
    if (is_nodata(value)) {
      throw Error("terrain grid: no height at (e " + number_text(e_m, 10) + ", n " +
                  number_text(n_m, 10) + "): a neighbouring sample is NODATA");
    }
    height += corner_weights[k] * value;
  }
  return height;
}

}  // namespace owsim
