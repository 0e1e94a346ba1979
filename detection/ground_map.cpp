#include "detection/ground_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace owsim {

GroundMap::GroundMap(double cell_m, double reach_m)
    : cell_m_(cell_m),
      side_(static_cast<std::int64_t>(std::ceil(2.0 * reach_m / cell_m)) + 4),
      cells_(static_cast<std::size_t>(side_ * side_)) {}

std::size_t GroundMap::slot(std::int64_t i, std::int64_t j) const {
  const std::int64_t a = ((i % side_) + side_) % side_;
  const std::int64_t b = ((j % side_) + side_) % side_;
  return static_cast<std::size_t>(a * side_ + b);
}

void GroundMap::add(double e, double n, double u) {
  const auto i = static_cast<std::int64_t>(std::floor(e / cell_m_));
  const auto j = static_cast<std::int64_t>(std::floor(n / cell_m_));
  ++version_;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  Cell& cell = cells_[slot(i, j)];
  if (cell.i != i || cell.j != j) {
    cell = Cell{i, j};
    cell.lowest.fill(kNone);
    cell.ground = kNone;
  }
  if (!(u < cell.lowest.back())) return;
  // Insert u among the kept lowest, then the lowest pair that agrees.
  std::size_t k = kKept - 1;
  for (; k > 0 && cell.lowest[k - 1] > u; --k) cell.lowest[k] = cell.lowest[k - 1];
  cell.lowest[k] = u;
  cell.ground = kNone;
  for (std::size_t a = 0; a + 1 < kKept; ++a) {
    if (cell.lowest[a + 1] - cell.lowest[a] <= kAgreeM) {
      cell.ground = cell.lowest[a + 1];
      break;
    }
  }
}

double GroundMap::ground_u(double e, double n) const {
  const auto i = static_cast<std::int64_t>(std::floor(e / cell_m_));
  const auto j = static_cast<std::int64_t>(std::floor(n / cell_m_));
  const Cell& own = cells_[slot(i, j)];
  const bool own_cell = own.i == i && own.j == j;
  if (own_cell && own.around_version == version_) return own.around;
  double lowest = std::numeric_limits<double>::infinity();
  for (std::int64_t di = -1; di <= 1; ++di) {
    for (std::int64_t dj = -1; dj <= 1; ++dj) {
      const Cell& cell = cells_[slot(i + di, j + dj)];
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
