#pragma once
// The elevated points that are no wire, grouped into obstacles (DETECTION-SPEC §2): points in
// 8-connected 1 m plan cells form one group, and groups whose plan boxes lie within
// link_m + link_per_m × range of each other (the nearer group's range: a scan's points spread with
// range) join. Plan, not 3D: poles, trees and buildings stand upright, and what stands under or
// over another thing is one obstacle to a pilot.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "detection/detector_params.hpp"
#include "detection/obstacle_class.hpp"

namespace owsim {

struct PointCluster {
  std::vector<std::uint32_t> points;  // indices into the points searched, ascending
};

// Reused buffers of find_clusters.
struct ClusterScratch {
  std::vector<std::uint32_t> parent;
};

// The clusters of the points with `skip[p] == 0`, ordered by their first point.
void find_clusters(std::span<const ObstaclePoint> points, std::span<const std::uint8_t> skip,
                   const DetectorParams& params, ClusterScratch& scratch,
                   std::vector<PointCluster>& out);

// The square of the horizontal gap between two plan boxes (0 when they overlap).
[[nodiscard]] double plan_gap_squared_m2(const Eigen::Vector2d& lo_a, const Eigen::Vector2d& hi_a,
                                const Eigen::Vector2d& lo_b, const Eigen::Vector2d& hi_b);

}  // namespace owsim
