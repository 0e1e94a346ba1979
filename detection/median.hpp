#pragma once
// The median of a list of values, found in place (the values are reordered); NaN for none.
#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>

namespace owsim {

// The upper median (the element at size / 2 in order): the detector's medians of clearances and
// offsets are taken over the points themselves, never between two of them.
inline double median_of(std::span<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace owsim
