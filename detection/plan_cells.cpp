#include "detection/plan_cells.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace owsim {

void sort_by_cell(std::vector<CellPoint>& keyed, std::vector<CellPoint>& buffer) {
  if (keyed.size() < 2) return;  // in order already (and no box to take)
  std::int64_t i_lo = INT64_MAX, i_hi = INT64_MIN, j_lo = INT64_MAX, j_hi = INT64_MIN;
  for (const CellPoint& k : keyed) {
    i_lo = std::min(i_lo, plan_cell_i(k.key));
    i_hi = std::max(i_hi, plan_cell_i(k.key));
    j_lo = std::min(j_lo, plan_cell_j(k.key));
    j_hi = std::max(j_hi, plan_cell_j(k.key));
  }
  const auto columns = static_cast<std::uint64_t>(j_hi - j_lo) + 1;
  const auto rows = static_cast<std::uint64_t>(i_hi - i_lo) + 1;
  constexpr int kDigitBits = 11;
  constexpr std::uint64_t kDigits = std::uint64_t{1} << kDigitBits;
  if (rows > (std::uint64_t{1} << 31) / columns) {  // a box too large: sorted by comparison
    std::sort(keyed.begin(), keyed.end(), [](const CellPoint& a, const CellPoint& b) {
      return a.key != b.key ? a.key < b.key : a.point < b.point;
    });
    return;
  }
  const auto number = [&](const CellPoint& k) {
    return static_cast<std::uint64_t>(plan_cell_i(k.key) - i_lo) * columns +
           static_cast<std::uint64_t>(plan_cell_j(k.key) - j_lo);
  };
  const std::uint64_t largest = rows * columns - 1;
  buffer.resize(keyed.size());
  std::array<std::uint32_t, kDigits> count;
  for (int shift = 0; shift == 0 || (largest >> shift) != 0; shift += kDigitBits) {
    count.fill(0);
    for (const CellPoint& k : keyed) ++count[(number(k) >> shift) & (kDigits - 1)];
    std::uint32_t start = 0;
    for (std::uint32_t& c : count) start += std::exchange(c, start);
    for (const CellPoint& k : keyed) buffer[count[(number(k) >> shift) & (kDigits - 1)]++] = k;
    keyed.swap(buffer);
  }
}

}  // namespace owsim
