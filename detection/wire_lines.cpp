#include "detection/wire_lines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "detection/median.hpp"
#include "detection/plan_cells.hpp"

namespace owsim {
namespace {

constexpr int kDirections = 180;  // 1° apart over a half turn
constexpr double kOffsetBinM = 1.0;
constexpr double kVoteCellM = 1.0;
constexpr std::size_t kMaxPeaks = 96;

struct Direction {
  double cos_t, sin_t;
};

const std::array<Direction, kDirections>& directions() {
  static const std::array<Direction, kDirections> table = [] {
    std::array<Direction, kDirections> out{};
    for (int k = 0; k < kDirections; ++k) {
      const double t = k * std::numbers::pi / kDirections;
      out[static_cast<std::size_t>(k)] = {std::cos(t), std::sin(t)};
    }
    return out;
  }();
  return table;
}


struct Peak {
  std::uint16_t votes;
  std::uint32_t bin;
};

struct Chain {
  double end_s, end_u, slope;
  bool sloped;
  std::vector<std::uint32_t> points;
};

// A candidate's plan line and its points' span along it.
struct Line {
  Eigen::Vector2d centre, direction;
};

Line line_of(std::span<const ObstaclePoint> points, const std::vector<std::uint32_t>& members) {
  std::vector<Eigen::Vector3d> at;
  at.reserve(members.size());
  for (const std::uint32_t p : members) at.push_back(points[p].enu_m);
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& p : at) centre += p.head<2>();
  centre /= static_cast<double>(at.size());
  return {centre, plan_extent(at).axis};
}

double lateral_m(const Line& line, const Eigen::Vector2d& at) {
  const Eigen::Vector2d d = at - line.centre;
  return std::abs(d.x() * line.direction.y() - d.y() * line.direction.x());
}

// Whether candidates a and b lie on one conductor (step 5).
bool same_conductor(std::span<const ObstaclePoint> points, const WireCandidate& a, const Line& la,
                    const WireCandidate& b, const Line& lb, const DetectorParams& params) {
  constexpr double kSinMaxAngle = 0.052335956242943835;  // sin 3°
  const double cross = la.direction.x() * lb.direction.y() - la.direction.y() * lb.direction.x();
  if (std::abs(cross) > kSinMaxAngle) return false;
  if (lateral_m(la, lb.centre) > params.wire_band_m || lateral_m(lb, la.centre) > params.wire_band_m) {
    return false;
  }
  // The facing ends: a's point nearest along the line to b's centre, and b's to a's.
  const auto s_of = [&](std::uint32_t p) {
    return (points[p].enu_m.head<2>() - la.centre).dot(la.direction);
  };
  const double sb = (lb.centre - la.centre).dot(la.direction);
  const double sa = 0.0;
  std::uint32_t end_a = a.points.front(), end_b = b.points.front();
  for (const std::uint32_t p : a.points) {
    if (std::abs(s_of(p) - sb) < std::abs(s_of(end_a) - sb)) end_a = p;
  }
  for (const std::uint32_t p : b.points) {
    if (std::abs(s_of(p) - sa) < std::abs(s_of(end_b) - sa)) end_b = p;
  }
  const double gap = std::abs(s_of(end_a) - s_of(end_b));
  return std::abs(points[end_a].enu_m.z() - points[end_b].enu_m.z()) <=
         params.wire_band_m + 0.10 * gap;
}

// Whether a chain is a piece of a line (step 4): longer than 2 m and three times its width — a
// pole's or a tree's points in a band across it are not.
bool piece_of_line(double length_m, double width_m) {
  return length_m > 2.0 && length_m > 3.0 * width_m;
}

}  // namespace

void find_wire_candidates(std::span<const ObstaclePoint> points,
                          std::span<const std::uint8_t> eligible, const Eigen::Vector2d& aircraft_en,
                          const DetectorParams& params, WireSearchScratch& scratch,
                          std::vector<WireCandidate>& out) {
  out.clear();
  if (points.size() < static_cast<std::size_t>(params.min_points)) return;
  const auto& table = directions();
  const int offsets = 2 * static_cast<int>(std::ceil(params.max_range_m / kOffsetBinM)) + 3;
  const double offset_zero = offsets / 2 * kOffsetBinM;
  const auto least = static_cast<std::uint16_t>(params.min_points);
  const auto row_size = static_cast<std::size_t>(offsets);
  if (scratch.rows.size() != 3 * row_size) scratch.rows.assign(3 * row_size, 0);

  // 1. One vote per occupied plan cell and direction.
  scratch.cells.clear();
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (eligible[p]) scratch.cells.push_back(plan_cell_key(points[p].enu_m.x(), points[p].enu_m.y(), kVoteCellM));
  }
  std::sort(scratch.cells.begin(), scratch.cells.end());
  scratch.cells.erase(std::unique(scratch.cells.begin(), scratch.cells.end()), scratch.cells.end());
  const std::size_t cells = scratch.cells.size();
  scratch.cell_x.resize(cells);
  scratch.cell_y.resize(cells);
  const std::size_t quarter = (cells + 3) / 4;
  scratch.cell_bin.assign(4 * quarter, -1);  // the ones past the cells stay off the table
  for (std::size_t c = 0; c < cells; ++c) {
    const std::uint64_t key = scratch.cells[c];
    scratch.cell_x[c] =
        (static_cast<double>(plan_cell_i(key)) + 0.5) * kVoteCellM - aircraft_en.x();
    scratch.cell_y[c] =
        (static_cast<double>(plan_cell_j(key)) + 0.5) * kVoteCellM - aircraft_en.y();
  }
  // 2. Peaks: local maxima (ties to the lower bin) with at least min_points votes. Direction k's
  // are decided once direction k + 1 is counted; a bin's index in the whole table is
  // k × offsets + its offset bin.
  std::vector<Peak> peaks;
  const auto row_of = [&](int k) { return scratch.rows.data() + (k % 3) * row_size; };
  const auto decide = [&](int k) {
    const std::uint16_t* rows[3] = {k > 0 ? row_of(k - 1) : nullptr, row_of(k),
                                    k + 1 < kDirections ? row_of(k + 1) : nullptr};
    for (const std::uint32_t b : scratch.full[static_cast<std::size_t>(k % 3)]) {
      const std::uint16_t v = rows[1][b];
      bool peak = true;
      for (int dk = -1; dk <= 1 && peak; ++dk) {
        const std::uint16_t* row = rows[dk + 1];
        if (row == nullptr) continue;
        for (int db = -1; db <= 1 && peak; ++db) {
          if (dk == 0 && db == 0) continue;
          const int bb = static_cast<int>(b) + db;
          if (bb < 0 || bb >= offsets) continue;
          const std::uint16_t w = row[bb];
          // The neighbour's index is the lower one when its direction is, or its offset in this one.
          if (w > v || (w == v && (dk < 0 || (dk == 0 && db < 0)))) peak = false;
        }
      }
      if (peak) peaks.push_back({v, static_cast<std::uint32_t>(k * offsets) + b});
    }
  };
  const auto clear = [&](int k) {
    std::uint16_t* row = row_of(k);
    std::fill(row, row + row_size, std::uint16_t{0});
    scratch.full[static_cast<std::size_t>(k % 3)].clear();
  };
  for (int k = 0; k < kDirections; ++k) {
    if (k >= 3) clear(k);  // the row of direction k − 3, decided and done with
    const Direction& d = table[static_cast<std::size_t>(k)];
    const auto table_end = static_cast<double>(offsets);
    for (std::size_t c = 0; c < cells; ++c) {
      // ⌊·⌋ of a value ≥ 0 by truncation; one < 0 is off the table.
      const double at_m = (scratch.cell_x[c] * d.cos_t + scratch.cell_y[c] * d.sin_t +
                           offset_zero) / kOffsetBinM;
      const bool on_table = at_m >= 0.0 && at_m < table_end;
      scratch.cell_bin[c] = on_table ? static_cast<std::int32_t>(at_m) : -1;
    }
    std::uint16_t* row = row_of(k);
    std::vector<std::uint32_t>& full = scratch.full[static_cast<std::size_t>(k % 3)];
    // The cells in four interleaved runs: cells next to each other (in key order) vote for the
    // same bins, and one increment after another of the same counter waits for the last store.
    for (std::size_t c = 0; c < quarter; ++c) {
      for (std::size_t run = 0; run < 4; ++run) {
        const std::int32_t bin = scratch.cell_bin[c + run * quarter];
        if (bin < 0) continue;
        std::uint16_t& v = row[bin];
        if (v < UINT16_MAX) ++v;
        if (v == least) full.push_back(static_cast<std::uint32_t>(bin));
      }
    }
    if (k > 0) decide(k - 1);
  }
  decide(kDirections - 1);
  for (int k = kDirections - 3; k < kDirections; ++k) clear(k);
  // The kMaxPeaks strongest (a total order: bins are distinct).
  const std::size_t kept = std::min(peaks.size(), kMaxPeaks);
  std::partial_sort(peaks.begin(), peaks.begin() + static_cast<std::ptrdiff_t>(kept), peaks.end(),
                    [](const Peak& a, const Peak& b) {
                      return a.votes != b.votes ? a.votes > b.votes : a.bin < b.bin;
                    });
  peaks.resize(kept);

  // 3–4. Each peak's points, chained along its line.
  // The points not yet taken by a piece of line, with their plan offsets from the aircraft.
  scratch.taken.assign(points.size(), 0);
  scratch.open.clear();
  scratch.open_e.clear();
  scratch.open_n.clear();
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (!eligible[p]) continue;
    scratch.open.push_back(p);
    scratch.open_e.push_back(points[p].enu_m.x() - aircraft_en.x());
    scratch.open_n.push_back(points[p].enu_m.y() - aircraft_en.y());
  }
  std::vector<Chain> chains;
  for (const Peak& peak : peaks) {
    const auto k = static_cast<std::size_t>(peak.bin / static_cast<std::uint32_t>(offsets));
    const Direction& d = table[k];
    double offset =
        (static_cast<double>(peak.bin % static_cast<std::uint32_t>(offsets)) + 0.5) * kOffsetBinM -
        offset_zero;
    const auto lateral = [&](const ObstaclePoint& p) {
      return (p.enu_m.x() - aircraft_en.x()) * d.cos_t + (p.enu_m.y() - aircraft_en.y()) * d.sin_t -
             offset;
    };
    // Refine the offset to the median of the points within a bin of the band. The points near the
    // line once: the refined line moves by at most band + half a bin, so its inliers lie within
    // 2 × band + a bin of the peak's line.
    const double half_bin = 0.5 * kOffsetBinM;
    const double reach = 2.0 * params.wire_band_m + 2.0 * half_bin;
    scratch.near.clear();
    scratch.offsets.clear();
    const std::size_t open = scratch.open.size();
    scratch.open_t.resize(open);
    for (std::size_t o = 0; o < open; ++o) {  // lateral(), on vector lanes
      scratch.open_t[o] = scratch.open_e[o] * d.cos_t + scratch.open_n[o] * d.sin_t - offset;
    }
    for (std::size_t o = 0; o < open; ++o) {
      const double t = scratch.open_t[o];
      if (std::abs(t) > reach) continue;
      scratch.near.push_back(scratch.open[o]);
      if (std::abs(t) <= params.wire_band_m + half_bin) scratch.offsets.push_back(t);
    }
    if (scratch.offsets.size() < static_cast<std::size_t>(params.min_points)) continue;
    offset += median_of(scratch.offsets);

    scratch.inliers.clear();
    for (const std::uint32_t p : scratch.near) {
      if (std::abs(lateral(points[p])) <= params.wire_band_m) scratch.inliers.push_back(p);
    }
    if (scratch.inliers.size() < static_cast<std::size_t>(params.min_points)) continue;
    const Eigen::Vector2d along(-d.sin_t, d.cos_t);
    const auto s_of = [&](std::uint32_t p) {
      return (points[p].enu_m.head<2>() - aircraft_en).dot(along);
    };
    std::sort(scratch.inliers.begin(), scratch.inliers.end(), [&](std::uint32_t a, std::uint32_t b) {
      const double sa = s_of(a), sb = s_of(b);
      return sa != sb ? sa < sb : a < b;
    });

    chains.clear();
    for (const std::uint32_t p : scratch.inliers) {
      const double s = s_of(p), u = points[p].enu_m.z();
      const double gap = params.wire_gap_m + params.wire_gap_per_m * points[p].range_m;
      Chain* best = nullptr;
      double best_miss = 0.0;
      for (Chain& chain : chains) {
        const double ds = s - chain.end_s;
        if (ds > gap) continue;
        const double predicted = chain.end_u + (chain.sloped ? chain.slope * ds : 0.0);
        const double miss = std::abs(u - predicted);
        const double tolerance = params.wire_band_m + (chain.sloped ? 0.10 : 0.25) * ds;
        if (miss <= tolerance && (best == nullptr || miss < best_miss)) {
          best = &chain;
          best_miss = miss;
        }
      }
      if (best == nullptr) {
        chains.push_back({s, u, 0.0, false, {p}});
        continue;
      }
      const double ds = s - best->end_s;
      if (ds > 1.0) {
        best->slope = (u - best->end_u) / ds;
        best->sloped = true;
      }
      best->end_s = s;
      best->end_u = u;
      best->points.push_back(p);
    }

    bool any_taken = false;
    for (Chain& chain : chains) {
      if (chain.points.size() < static_cast<std::size_t>(params.min_points)) continue;
      const double length = s_of(chain.points.back()) - s_of(chain.points.front());
      double lo = lateral(points[chain.points.front()]), hi = lo;
      for (const std::uint32_t p : chain.points) {
        const double t = lateral(points[p]);
        lo = std::min(lo, t);
        hi = std::max(hi, t);
      }
      if (!piece_of_line(length, hi - lo)) continue;
      for (const std::uint32_t p : chain.points) scratch.taken[p] = 1;
      out.push_back({std::move(chain.points), along, length, hi - lo});
      any_taken = true;
    }
    if (!any_taken) continue;
    std::size_t left = 0;  // the open points without those taken, in order
    for (std::size_t o = 0; o < scratch.open.size(); ++o) {
      if (scratch.taken[scratch.open[o]]) continue;
      scratch.open[left] = scratch.open[o];
      scratch.open_e[left] = scratch.open_e[o];
      scratch.open_n[left] = scratch.open_n[o];
      ++left;
    }
    scratch.open.resize(left);
    scratch.open_e.resize(left);
    scratch.open_n.resize(left);
  }

  // 5. Pieces of one conductor joined, in candidate order.
  std::vector<Line> lines;
  lines.reserve(out.size());
  for (const WireCandidate& candidate : out) lines.push_back(line_of(points, candidate.points));
  std::vector<std::size_t> parent(out.size());
  for (std::size_t c = 0; c < out.size(); ++c) parent[c] = c;
  const auto root = [&](std::size_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  for (std::size_t a = 0; a < out.size(); ++a) {
    for (std::size_t b = a + 1; b < out.size(); ++b) {
      if (root(a) == root(b)) continue;
      if (same_conductor(points, out[a], lines[a], out[b], lines[b], params)) {
        parent[root(b)] = root(a);
      }
    }
  }
  std::vector<WireCandidate> joined;
  std::vector<std::ptrdiff_t> slot(out.size(), -1);
  for (std::size_t c = 0; c < out.size(); ++c) {
    const std::size_t r = root(c);
    if (slot[r] < 0) {
      slot[r] = static_cast<std::ptrdiff_t>(joined.size());
      joined.emplace_back();
    }
    WireCandidate& into = joined[static_cast<std::size_t>(slot[r])];
    into.points.insert(into.points.end(), out[c].points.begin(), out[c].points.end());
  }
  out.clear();
  for (WireCandidate& wire : joined) {
    std::sort(wire.points.begin(), wire.points.end());
    std::vector<Eigen::Vector3d> at;
    for (const std::uint32_t p : wire.points) at.push_back(points[p].enu_m);
    const PlanExtent extent = plan_extent(at);
    if (!wire_shaped(extent.length_m, extent.width_m, params)) continue;  // its points go back
    wire.direction = extent.axis;
    wire.length_m = extent.length_m;
    wire.width_m = extent.width_m;
    out.push_back(std::move(wire));
  }
}

}  // namespace owsim
