#include "detection/ground_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detection/plan_cells.hpp"

namespace owsim {

GroundMap::GroundMap(double cell_m, double reach_m)
    : cell_m_(cell_m),
      side_(static_cast<std::int64_t>(std::ceil(2.0 * reach_m / cell_m)) + 4),
      per_side_(1.0 / static_cast<double>(side_)),
      cells_(static_cast<std::size_t>(side_ * side_)) {}

std::int64_t GroundMap::wrapped(std::int64_t i) const {
  // The quotient's estimate is off by at most one for |i| < 2^50; the remainder corrects it.
  std::int64_t r = i - cell_index(static_cast<double>(i) * per_side_, 1.0) * side_;
  if (r < 0) r += side_;
  if (r >= side_) r -= side_;
  return r;
}

std::size_t GroundMap::slot(std::int64_t a, std::int64_t b) const {
  return static_cast<std::size_t>(a * side_ + b);
}

GroundMap::Place GroundMap::place_of(double e, double n) const {
  const std::int64_t i = cell_index(e, cell_m_);
  const std::int64_t j = cell_index(n, cell_m_);
  return {i, j, wrapped(i), wrapped(j)};
}

void GroundMap::add(const Place& at, double u) {
  const auto [i, j, a, b] = at;
  ++version_;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  Cell& cell = cells_[slot(a, b)];
  if (cell.i != i || cell.j != j) {
    cell = Cell{i, j};
    cell.lowest.fill(kNone);
    cell.ground = kNone;
  }
  // The kKept lowest of the kept and u, by a network of min and max rather than branches on
  // where u goes (which a scan's returns make unpredictable); u no lower than all of them leaves
  // them as they are. Then the lowest pair that agrees.
  double carried = u;
  for (double& kept : cell.lowest) {
    const double low = std::min(kept, carried);
    carried = std::max(kept, carried);
    kept = low;
  }
  double ground = kNone;
  for (std::size_t k = kKept - 1; k-- > 0;) {
    ground = cell.lowest[k + 1] - cell.lowest[k] <= kAgreeM ? cell.lowest[k + 1] : ground;
  }
  cell.ground = ground;
}

double GroundMap::ground_u(const Place& at) const {
  const auto [i, j, a, b] = at;
  const Cell& own = cells_[slot(a, b)];
  const bool own_cell = own.i == i && own.j == j;
  if (own_cell && own.around_version == version_) return own.around;
  // The 3×3 cells' rows and columns, wrapped around the table's edges.
  const std::int64_t rows[3] = {a == 0 ? side_ - 1 : a - 1, a, a + 1 == side_ ? 0 : a + 1};
  const std::int64_t columns[3] = {b == 0 ? side_ - 1 : b - 1, b, b + 1 == side_ ? 0 : b + 1};
  double lowest = std::numeric_limits<double>::infinity();
  for (std::int64_t di = -1; di <= 1; ++di) {
    for (std::int64_t dj = -1; dj <= 1; ++dj) {
      const Cell& cell = cells_[slot(rows[di + 1], columns[dj + 1])];
      if (cell.i == i + di && cell.j == j + dj) lowest = std::min(lowest, cell.ground);
    }
  }
  const double ground = std::isinf(lowest) ? std::numeric_limits<double>::quiet_NaN() : lowest;
  if (own_cell) {
    own.around = ground;
    own.around_version = version_;
  }
  return ground;
}

}  // namespace owsim
