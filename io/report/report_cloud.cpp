#include "io/report/report_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

std::size_t class_slot(std::uint8_t surface) {
  return surface < kSurfaceClassCount ? surface : kSurfaceClassCount;
}

// How many of each class to keep within `budget`: smallest classes first, each all it has or an
// equal share of what is left.
std::array<std::uint64_t, kCloudClassSlots> class_budgets(
    const std::array<std::uint64_t, kCloudClassSlots>& counts, std::uint64_t budget) {
  std::array<std::size_t, kCloudClassSlots> order{};
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return counts[a] < counts[b]; });
  std::array<std::uint64_t, kCloudClassSlots> keep{};
  std::uint64_t left = budget;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint64_t share = left / (order.size() - i);
    keep[order[i]] = std::min(counts[order[i]], share);
    left -= keep[order[i]];
  }
  return keep;
}

}  // namespace

ReportCloud report_cloud(const ReportPoints& points, std::uint64_t max_points) {
  if (max_points < 1) throw input_error("--max-points", "must be at least 1");
  ReportCloud cloud;
  cloud.total = points.size();
  const std::array<std::vector<float> const*, 3> axes = {&points.e_m, &points.n_m, &points.u_m};
  cloud.box_min.fill(std::numeric_limits<double>::infinity());
  cloud.box_max.fill(-std::numeric_limits<double>::infinity());
  std::vector<bool> finite(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    finite[i] = std::isfinite((*axes[0])[i]) && std::isfinite((*axes[1])[i]) &&
                std::isfinite((*axes[2])[i]);
    if (!finite[i]) continue;
    ++cloud.total_by_class[class_slot(points.surface[i])];
    for (std::size_t a = 0; a < 3; ++a) {
      cloud.box_min[a] = std::min<double>(cloud.box_min[a], (*axes[a])[i]);
      cloud.box_max[a] = std::max<double>(cloud.box_max[a], (*axes[a])[i]);
    }
  }
  const std::array<std::uint64_t, kCloudClassSlots> keep =
      class_budgets(cloud.total_by_class, max_points);
  std::array<std::uint64_t, kCloudClassSlots> seen{};
  std::array<double, 3> step{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double size = cloud.box_max[a] - cloud.box_min[a];
    step[a] = size > 0 ? size / 65535.0 : 1.0;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!finite[i]) continue;
    const std::size_t slot = class_slot(points.surface[i]);
    // The n-th return of a class is kept when it crosses the next multiple of total/keep.
    const std::uint64_t n = seen[slot]++;
    if (keep[slot] == 0 || (n * keep[slot]) / cloud.total_by_class[slot] ==
                               ((n + 1) * keep[slot]) / cloud.total_by_class[slot]) {
      continue;
    }
    ++cloud.shown_by_class[slot];
    for (std::size_t a = 0; a < 3; ++a) {
      const double q = std::round(((*axes[a])[i] - cloud.box_min[a]) / step[a]);
      cloud.xyz.push_back(static_cast<std::uint16_t>(std::clamp(q, 0.0, 65535.0)));
    }
    cloud.surface.push_back(points.surface[i]);
    cloud.range_dm.push_back(range_decimetres(points.range_m[i]));
  }
  if (cloud.xyz.empty()) {
    cloud.box_min.fill(0.0);
    cloud.box_max.fill(0.0);
  }
  return cloud;
}

}  // namespace owsim
