#include "detection/wire_lines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "detection/median.hpp"

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

// A plan cell's key: 32 bits of each index (offset so that they sort as signed numbers).
std::uint64_t cell_key(double e, double n) {
  const auto i = static_cast<std::int64_t>(std::floor(e / kVoteCellM)) + (std::int64_t{1} << 31);
  const auto j = static_cast<std::int64_t>(std::floor(n / kVoteCellM)) + (std::int64_t{1} << 31);
  return (static_cast<std::uint64_t>(i) << 32) | static_cast<std::uint32_t>(j);
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
  const std::size_t bins = static_cast<std::size_t>(kDirections) * offsets;
  if (scratch.votes.size() != bins) scratch.votes.assign(bins, 0);
  scratch.touched.clear();
  scratch.full.clear();
  const auto least = static_cast<std::uint16_t>(params.min_points);

  // 1. One vote per occupied plan cell and direction.
  scratch.cells.clear();
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    if (eligible[p]) scratch.cells.push_back(cell_key(points[p].enu_m.x(), points[p].enu_m.y()));
  }
  std::sort(scratch.cells.begin(), scratch.cells.end());
  scratch.cells.erase(std::unique(scratch.cells.begin(), scratch.cells.end()), scratch.cells.end());
  for (const std::uint64_t key : scratch.cells) {
    const double x = (static_cast<double>(static_cast<std::int64_t>(key >> 32) -
                                          (std::int64_t{1} << 31)) + 0.5) * kVoteCellM -
                     aircraft_en.x();
    const double y = (static_cast<double>(static_cast<std::int64_t>(key & 0xFFFFFFFFu) -
                                          (std::int64_t{1} << 31)) + 0.5) * kVoteCellM -
                     aircraft_en.y();
    for (int k = 0; k < kDirections; ++k) {
      const Direction& d = table[static_cast<std::size_t>(k)];
      // ⌊·⌋ of a value ≥ 0 by truncation; one < 0 is off the table.
      const double at_m = (x * d.cos_t + y * d.sin_t + offset_zero) / kOffsetBinM;
      if (!(at_m >= 0.0)) continue;
      const int bin = static_cast<int>(at_m);
      if (bin >= offsets) continue;
      const auto at = static_cast<std::uint32_t>(k * offsets + bin);
      std::uint16_t& v = scratch.votes[at];
      if (v == 0) scratch.touched.push_back(at);
      if (v < UINT16_MAX) ++v;
      if (v == least) scratch.full.push_back(at);
    }
  }

  // 2. Peaks: local maxima (ties to the lower bin) with at least min_points votes.
  std::vector<Peak> peaks;
  for (const std::uint32_t at : scratch.full) {
    const int k = static_cast<int>(at) / offsets, b = static_cast<int>(at) % offsets;
    const std::uint16_t v = scratch.votes[at];
    bool peak = true;
    for (int dk = -1; dk <= 1 && peak; ++dk) {
      for (int db = -1; db <= 1 && peak; ++db) {
        if (dk == 0 && db == 0) continue;
        const int kk = k + dk, bb = b + db;
        if (kk < 0 || kk >= kDirections || bb < 0 || bb >= offsets) continue;
        const auto other = static_cast<std::uint32_t>(kk * offsets + bb);
        const std::uint16_t w = scratch.votes[other];
        if (w > v || (w == v && other < at)) peak = false;
      }
    }
    if (peak) peaks.push_back({v, at});
  }
  for (const std::uint32_t at : scratch.touched) scratch.votes[at] = 0;
  std::sort(peaks.begin(), peaks.end(), [](const Peak& a, const Peak& b) {
    return a.votes != b.votes ? a.votes > b.votes : a.bin < b.bin;
  });
  if (peaks.size() > kMaxPeaks) peaks.resize(kMaxPeaks);

  // 3–4. Each peak's points, chained along its line.
  scratch.taken.assign(points.size(), 0);
  scratch.open.clear();
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    scratch.taken[p] = eligible[p] ? 0 : 1;
    if (eligible[p]) scratch.open.push_back(p);
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
    for (const std::uint32_t p : scratch.open) {
      if (scratch.taken[p]) continue;
      const double t = lateral(points[p]);
      if (std::abs(t) > reach) continue;
      scratch.near.push_back(p);
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
    }
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
