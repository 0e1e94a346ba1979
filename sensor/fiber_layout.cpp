#include "sensor/fiber_layout.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

void check_fiber(const ScanParams& p, int fiber) {
  if (fiber < 1 || fiber > p.fibers_per_line) {
    throw Error("fiber " + std::to_string(fiber) + " is outside 1.." +
                std::to_string(p.fibers_per_line));
  }
}

// α of fiber i (1-based, not the reference) of the linear default layout.
double default_alpha_deg(int fibers_per_line, int fiber) {
  const int left = left_half_fibers(fibers_per_line);
  const int right = fibers_per_line - 1 - left;
  if (fiber <= left) {
    if (left == 1) return -kFiberEdgeAlphaDeg;
    return -kFiberEdgeAlphaDeg + kFiberEdgeAlphaDeg * (fiber - 1) / (left - 1);
  }
  if (right == 1) return kFiberEdgeAlphaDeg;
  return kFiberEdgeAlphaDeg - kFiberEdgeAlphaDeg * (fiber - left - 1) / (right - 1);
}

}  // namespace

bool is_reference_fiber(const ScanParams& p, int fiber) { return fiber == p.reference_fiber(); }

int fiber_at_slot(const ScanParams& p, int slot) {
  const int fibers = p.fibers_per_line;
  if (slot < 0 || slot >= fibers) {
    throw Error("slot " + std::to_string(slot) + " is outside the line 0.." +
                std::to_string(fibers - 1));
  }
  const int left = left_half_fibers(fibers);
  if (p.fiber_order == FiberOrder::crosstalk_resorted || slot < left || slot == fibers - 1) {
    return slot + 1;
  }
  return fibers - 1 - (slot - left);  // sequential right half: 127, 126, …, 65
}

int slot_of_fiber(const ScanParams& p, int fiber) {
  check_fiber(p, fiber);
  const int fibers = p.fibers_per_line;
  const int left = left_half_fibers(fibers);
  if (p.fiber_order == FiberOrder::crosstalk_resorted || fiber <= left || fiber == fibers) {
    return fiber - 1;
  }
  return left + (fibers - 1 - fiber);
}

std::vector<double> default_alpha_table_deg(int fibers_per_line) {
  std::vector<double> table;
  if (fibers_per_line < 2) return table;
  table.reserve(static_cast<std::size_t>(fibers_per_line - 1));
  for (int fiber = 1; fiber < fibers_per_line; ++fiber) {
    table.push_back(default_alpha_deg(fibers_per_line, fiber));
  }
  return table;
}

double fiber_alpha_deg(const ScanParams& p, int fiber) {
  check_fiber(p, fiber);
  if (is_reference_fiber(p, fiber)) return std::numeric_limits<double>::quiet_NaN();
  if (p.alpha_table_deg.empty()) return default_alpha_deg(p.fibers_per_line, fiber);
  if (p.alpha_table_deg.size() != static_cast<std::size_t>(p.fibers_per_line - 1)) {
    throw input_error("sensor.alpha_table_deg",
                      "holds " + std::to_string(p.alpha_table_deg.size()) +
                          " angles, fibers_per_line " + std::to_string(p.fibers_per_line) +
                          " needs " + std::to_string(p.fibers_per_line - 1));
  }
  return p.alpha_table_deg[static_cast<std::size_t>(fiber - 1)];
}

std::vector<int> fibers_top_down(const ScanParams& p) {
  std::vector<int> fibers;
  for (int fiber = 1; fiber <= p.fibers_per_line; ++fiber) {
    if (!is_reference_fiber(p, fiber)) fibers.push_back(fiber);
  }
  std::stable_sort(fibers.begin(), fibers.end(),
                   [&](int a, int b) { return fiber_alpha_deg(p, a) > fiber_alpha_deg(p, b); });
  return fibers;
}

double sawtooth_deg(const ScanParams& p, int fiber) {
  return (fiber % 2 != 0) ? -p.sawtooth_deg : p.sawtooth_deg;
}

}  // namespace owsim
