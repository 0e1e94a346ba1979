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
#include "detection/plan_cells.hpp"

namespace owsim {

struct PointCluster {
  std::vector<std::uint32_t> points;  // indices into the points searched, ascending
};

// Reused buffers of find_clusters.
struct ClusterScratch {
  struct Cell {
    std::uint64_t key;
    std::uint32_t first, count;  // its points in `keyed`
  };
  std::vector<CellPoint> keyed;
  std::vector<CellPoint> sorted;  // the radix sort's other half
  std::vector<Cell> cells;
  std::vector<std::uint32_t> parent;
  std::vector<std::uint32_t> root_of_point;
  std::vector<std::int64_t> cluster_of;  // by root cell
  std::vector<std::uint8_t> left_out;  // find_clusters_without's
  std::vector<PointCluster> again;
};

// The clusters of the points with `skip[p] == 0`, ordered by their first point.
void find_clusters(std::span<const ObstaclePoint> points, std::span<const std::uint8_t> skip,
                   const DetectorParams& params, ClusterScratch& scratch,
                   std::vector<PointCluster>& out);

// find_clusters(points, skip, …) from `all`, the clusters of the same points with nothing skipped:
// a cluster of `all` with no skipped point is one of the result as it is (taking points away only
// splits clusters and never links them: each group keeps its cells, boxes only shrink and ranges
// only grow), so only the clusters that lose points are clustered again. The same clusters, in the
// same order, as find_clusters.
void find_clusters_without(std::span<const ObstaclePoint> points,
                           std::span<const std::uint8_t> skip,
                           std::span<const PointCluster> all, const DetectorParams& params,
                           ClusterScratch& scratch, std::vector<PointCluster>& out);

// The square of the horizontal gap between two plan boxes (0 when they overlap).
[[nodiscard]] double plan_gap_squared_m2(const Eigen::Vector2d& lo_a, const Eigen::Vector2d& hi_a,
                                const Eigen::Vector2d& lo_b, const Eigen::Vector2d& hi_b);

}  // namespace owsim
