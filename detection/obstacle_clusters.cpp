#include "detection/obstacle_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detection/plan_cells.hpp"

namespace owsim {
namespace {

constexpr double kCellM = 1.0;

using Keyed = CellPoint;
using Cell = ClusterScratch::Cell;

std::uint32_t root_of(std::vector<std::uint32_t>& parent, std::uint32_t a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

void join(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b) {
  a = root_of(parent, a);
  b = root_of(parent, b);
  if (a == b) return;
  if (a < b) {
    parent[b] = a;
  } else {
    parent[a] = b;
  }
}


struct Group {
  Eigen::Vector2d lo, hi;
  double range_m;
  std::uint32_t cell;  // a cell of the group (its root)
};

}  // namespace

double plan_gap_squared_m2(const Eigen::Vector2d& lo_a, const Eigen::Vector2d& hi_a,
                           const Eigen::Vector2d& lo_b, const Eigen::Vector2d& hi_b) {
  const double dx = std::max({0.0, lo_b.x() - hi_a.x(), lo_a.x() - hi_b.x()});
  const double dy = std::max({0.0, lo_b.y() - hi_a.y(), lo_a.y() - hi_b.y()});
  return dx * dx + dy * dy;
}

void find_clusters(std::span<const ObstaclePoint> points, std::span<const std::uint8_t> skip,
                   const DetectorParams& params, ClusterScratch& scratch,
                   std::vector<PointCluster>& out) {
  out.clear();
  // Points by plan cell: (cell, point) in cell order, a cell's points ascending.
  std::vector<Keyed>& keyed = scratch.keyed;
  keyed.clear();
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (skip[p]) continue;
    keyed.push_back({plan_cell_key(points[p].enu_m.x(), points[p].enu_m.y(), kCellM), p});
  }
  if (keyed.empty()) return;
  sort_by_cell(keyed, scratch.sorted);
  std::vector<Cell>& cells = scratch.cells;
  cells.clear();
  for (std::uint32_t k = 0; k < keyed.size(); ++k) {
    if (cells.empty() || cells.back().key != keyed[k].key) cells.push_back({keyed[k].key, k, 0});
    ++cells.back().count;
  }
  std::vector<std::uint32_t>& parent = scratch.parent;
  parent.resize(cells.size());
  for (std::uint32_t c = 0; c < cells.size(); ++c) parent[c] = c;
  // 8-connected cells (the forward half of the neighbourhood suffices): (i, j + 1) is the next cell
  // if any, and the row i + 1's cells j − 1 … j + 1 are found by a cursor that only moves forward.
  std::size_t cursor = 0;
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    const std::uint64_t key = cells[c].key;
    if (c + 1 < cells.size() && cells[c + 1].key == key + 1) join(parent, c, c + 1);
    const std::uint64_t first = key + (std::uint64_t{1} << 32) - 1;  // (i + 1, j − 1)
    while (cursor < cells.size() && cells[cursor].key < first) ++cursor;
    for (std::size_t o = cursor; o < cells.size() && cells[o].key <= first + 2; ++o) {
      join(parent, c, static_cast<std::uint32_t>(o));
    }
  }
  // Groups of connected cells with their plan boxes and nearest range.
  std::vector<std::int64_t> group_of(cells.size(), -1);
  std::vector<Group> groups;
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    const std::uint32_t root = root_of(parent, c);
    if (group_of[root] < 0) {
      group_of[root] = static_cast<std::int64_t>(groups.size());
      const Eigen::Vector2d inf(std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::infinity());
      groups.push_back({inf, -inf, std::numeric_limits<double>::infinity(), root});
    }
    Group& g = groups[static_cast<std::size_t>(group_of[root])];
    for (std::uint32_t k = cells[c].first; k < cells[c].first + cells[c].count; ++k) {
      const ObstaclePoint& p = points[keyed[k].point];
      g.lo = g.lo.cwiseMin(p.enu_m.head<2>());
      g.hi = g.hi.cwiseMax(p.enu_m.head<2>());
      g.range_m = std::min(g.range_m, p.range_m);
    }
  }
  // Groups within the link distance join: a sweep over the boxes in east order.
  std::vector<std::uint32_t> order(groups.size());
  for (std::uint32_t g = 0; g < groups.size(); ++g) order[g] = g;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return groups[a].lo.x() != groups[b].lo.x() ? groups[a].lo.x() < groups[b].lo.x() : a < b;
  });
  const double widest = params.link_m + params.link_per_m * params.max_range_m;
  for (std::size_t a = 0; a < order.size(); ++a) {
    const Group& ga = groups[order[a]];
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      const Group& gb = groups[order[b]];
      if (gb.lo.x() > ga.hi.x() + widest) break;
      const double link = params.link_m + params.link_per_m * std::min(ga.range_m, gb.range_m);
      if (plan_gap_squared_m2(ga.lo, ga.hi, gb.lo, gb.hi) <= link * link) {
        join(parent, ga.cell, gb.cell);
      }
    }
  }
  // Clusters: the points of each final root, in the order of their first points, each ascending.
  std::vector<std::uint32_t>& root_of_point = scratch.root_of_point;
  root_of_point.resize(points.size());
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    const std::uint32_t root = root_of(parent, c);
    for (std::uint32_t k = cells[c].first; k < cells[c].first + cells[c].count; ++k) {
      root_of_point[keyed[k].point] = root;
    }
  }
  std::vector<std::int64_t>& cluster_of = scratch.cluster_of;
  cluster_of.assign(cells.size(), -1);
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (skip[p]) continue;
    std::int64_t& cluster = cluster_of[root_of_point[p]];
    if (cluster < 0) {
      cluster = static_cast<std::int64_t>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(cluster)].points.push_back(p);
  }
}

void find_clusters_without(std::span<const ObstaclePoint> points,
                           std::span<const std::uint8_t> skip,
                           std::span<const PointCluster> all, const DetectorParams& params,
                           ClusterScratch& scratch, std::vector<PointCluster>& out) {
  out.clear();
  // Points of the clusters that lose none stay as they are; the others' are clustered again.
  std::vector<std::uint8_t>& left_out = scratch.left_out;
  left_out.assign(points.size(), 1);
  bool any_again = false;
  for (const PointCluster& cluster : all) {
    const bool loses = std::any_of(cluster.points.begin(), cluster.points.end(),
                                   [&](std::uint32_t p) { return skip[p] != 0; });
    if (!loses) {
      out.push_back(cluster);
      continue;
    }
    any_again = true;
    for (const std::uint32_t p : cluster.points) left_out[p] = skip[p];
  }
  if (!any_again) return;
  std::vector<PointCluster>& again = scratch.again;
  find_clusters(points, left_out, params, scratch, again);
  for (PointCluster& cluster : again) out.push_back(std::move(cluster));
  std::sort(out.begin(), out.end(), [](const PointCluster& a, const PointCluster& b) {
    return a.points.front() < b.points.front();
  });
}

}  // namespace owsim
