#pragma once
// The detector's grids (ground map, clusters, the wire search's votes, isolation, track voxels):
// which cell of a given size holds a coordinate, and a plan cell's key that sorts as its indices.
#include <cstdint>
#include <vector>

namespace owsim {

// ⌊x / size⌋ as an integer, for |x / size| < 2^62, without a call to floor (the baseline x86-64
// target has no rounding instruction, and the detector takes some 10^5 of these a frame).
[[nodiscard]] inline std::int64_t cell_index(double x, double size) {
  const double q = x / size;
  const auto toward_zero = static_cast<std::int64_t>(q);
  return static_cast<double>(toward_zero) > q ? toward_zero - 1 : toward_zero;
}

// The key of plan cell (i, j): 32 bits of each index, offset so that keys sort as (i, j) does and
// the key of (i, j + 1) is the key of (i, j) plus one.
[[nodiscard]] inline std::uint64_t plan_cell_key(std::int64_t i, std::int64_t j) {
  return (static_cast<std::uint64_t>(i + (std::int64_t{1} << 31)) << 32) |
         static_cast<std::uint32_t>(j + (std::int64_t{1} << 31));
}
[[nodiscard]] inline std::uint64_t plan_cell_key(double e, double n, double size) {
  return plan_cell_key(cell_index(e, size), cell_index(n, size));
}
[[nodiscard]] inline std::int64_t plan_cell_i(std::uint64_t key) {
  return static_cast<std::int64_t>(key >> 32) - (std::int64_t{1} << 31);
}
[[nodiscard]] inline std::int64_t plan_cell_j(std::uint64_t key) {
  return static_cast<std::int64_t>(key & 0xFFFFFFFFu) - (std::int64_t{1} << 31);
}

// A point and its plan cell's key.
struct CellPoint {
  std::uint64_t key;
  std::uint32_t point;
};

// `cell_points` (pushed in ascending point order) in (key, point) order: a stable radix sort of the
// cells' numbers within their bounding box, 11 bits a pass (a window's cells span a few thousand
// metres: two or three passes, against std::sort's dozen comparisons a point). `buffer` is the
// sort's other half.
void sort_by_cell(std::vector<CellPoint>& cell_points, std::vector<CellPoint>& buffer);

}  // namespace owsim
