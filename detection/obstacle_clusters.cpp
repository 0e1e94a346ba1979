#include "detection/obstacle_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace owsim {
namespace {

constexpr double kCellM = 1.0;

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

struct Cell {
  std::int64_t i, j;
  std::uint32_t first, count;  // its points in `keyed`
};

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
  // Points by plan cell.
  struct Keyed {
    std::int64_t i, j;
    std::uint32_t point;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(points.size());
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (skip[p]) continue;
    keyed.push_back({static_cast<std::int64_t>(std::floor(points[p].enu_m.x() / kCellM)),
                     static_cast<std::int64_t>(std::floor(points[p].enu_m.y() / kCellM)), p});
  }
  if (keyed.empty()) return;
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    return a.i != b.i ? a.i < b.i : a.j != b.j ? a.j < b.j : a.point < b.point;
  });
  std::vector<Cell> cells;
  for (std::uint32_t k = 0; k < keyed.size(); ++k) {
    if (cells.empty() || cells.back().i != keyed[k].i || cells.back().j != keyed[k].j) {
      cells.push_back({keyed[k].i, keyed[k].j, k, 0});
    }
    ++cells.back().count;
  }
  const auto find_cell = [&](std::int64_t i, std::int64_t j) -> std::int64_t {
    const auto it = std::lower_bound(cells.begin(), cells.end(), std::pair{i, j},
                                     [](const Cell& c, const std::pair<std::int64_t, std::int64_t>& v) {
                                       return c.i != v.first ? c.i < v.first : c.j < v.second;
                                     });
    if (it == cells.end() || it->i != i || it->j != j) return -1;
    return it - cells.begin();
  };
  std::vector<std::uint32_t>& parent = scratch.parent;
  parent.resize(cells.size());
  for (std::uint32_t c = 0; c < cells.size(); ++c) parent[c] = c;
  // 8-connected cells (the forward half of the neighbourhood suffices).
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    const std::pair<int, int> forward[] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
    for (const auto& [di, dj] : forward) {
      const std::int64_t other = find_cell(cells[c].i + di, cells[c].j + dj);
      if (other >= 0) join(parent, c, static_cast<std::uint32_t>(other));
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
  // Clusters: points of each final root, ordered by their first point.
  std::vector<std::int64_t> cluster_of(cells.size(), -1);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> members;  // (cluster root, point)
  members.reserve(keyed.size());
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    const std::uint32_t root = root_of(parent, c);
    for (std::uint32_t k = cells[c].first; k < cells[c].first + cells[c].count; ++k) {
      members.emplace_back(root, keyed[k].point);
    }
  }
  std::sort(members.begin(), members.end());
  for (std::size_t k = 0; k < members.size(); ++k) {
    if (k == 0 || members[k].first != members[k - 1].first) out.emplace_back();
    out.back().points.push_back(members[k].second);
  }
  std::sort(out.begin(), out.end(), [](const PointCluster& a, const PointCluster& b) {
    return a.points.front() < b.points.front();
  });
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
