#pragma once
// The 3D view's point cloud for `owsim view`: at most max_points returns, quantised to 16 bits per
// axis within their bounding box (so the page carries 6 bytes a position; the step is the box's
// size / 65535 in each axis, stated on the page), with their class and range.
//
// Level of detail for long flights: when there are more returns than max_points, the rare classes
// are kept whole and the common ones thinned evenly (every k-th return of the class): the budget
// is shared out over the classes from the smallest up, each taking all it has or an equal share
// of what is left. Which fraction of each class is shown is reported, for the page to state.
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/scene.hpp"
#include "io/report/report_points.hpp"

namespace owsim {

// kSurfaceClassCount classes, then returns of unknown class.
inline constexpr std::size_t kCloudClassSlots = kSurfaceClassCount + 1;

struct ReportCloud {
  std::uint64_t total = 0;  // returns in the folder
  std::array<std::uint64_t, kCloudClassSlots> total_by_class{};
  std::array<std::uint64_t, kCloudClassSlots> shown_by_class{};
  std::array<double, 3> box_min{}, box_max{};  // of the finite positions, local ENU metres
  std::vector<std::uint16_t> xyz;  // 3 per shown return: round((x − min)/(max − min) · 65535)
  std::vector<std::uint8_t> surface;    // SurfaceClass code, kUnknownSurface
  std::vector<std::uint16_t> range_dm;  // 0 unknown
  [[nodiscard]] std::size_t shown() const { return surface.size(); }
};

// Throws owsim::Error if max_points < 1.
[[nodiscard]] ReportCloud report_cloud(const ReportPoints& points, std::uint64_t max_points);

}  // namespace owsim
