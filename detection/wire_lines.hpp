#pragma once
// Wire candidates among the elevated points (DETECTION-SPEC §2; the sensor maker's approach,
// patent US 6,747,576: lines in the horizontal plane, then curves in their vertical plane).
//
// 1. Hough transform in plan: every occupied 1 m plan cell votes once for each of 180 line
//    directions (1° apart) at its signed distance from the aircraft (1 m bins), so a pole or a
//    tree (a few cells) casts few votes for any line and a span (a cell every few metres along it)
//    many for one.
// 2. The peaks (local maxima with at least min_points votes), strongest first: the points within
//    wire_band_m of the peak's line, its offset refined to their median.
// 3. Along the line, the points are joined into chains in the line's vertical plane: each point,
//    in order along the line, continues the chain whose extrapolated height is nearest, if the gap
//    is at most wire_gap_m + wire_gap_per_m × range and the height within wire_band_m + 10 % of
//    the gap (25 % for a chain of one point) — so conductors stacked on one line in plan stay
//    apart, and a conductor stays one across the gaps a scan leaves at range.
// 4. A chain of at least min_points points longer than 2 m and than three times its width is a
//    piece of a line; its points are taken from the later peaks.
// 5. Pieces on one line join (a conductor cut by a scan's gaps, or found in pieces by peaks a
//    degree apart): their plan lines within 3° and each one's centre within wire_band_m of the
//    other's line, and their facing ends' heights within wire_band_m + 10 % of the gap between
//    them (conductors stacked on one line in plan stay apart). A joined line whose length over
//    width exceeds wire_min_aspect is a wire candidate; the other pieces' points are left.
// Whether a candidate is a WIRE (isolation, clearance) is decided by the caller, who knows the
// other objects.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "detection/detector_params.hpp"
#include "detection/obstacle_class.hpp"

namespace owsim {

struct WireCandidate {
  std::vector<std::uint32_t> points;  // indices into the points searched, in order along the line
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // plan, unit
  double length_m = 0.0;  // along the line
  double width_m = 0.0;   // across it, in plan
};

// Reused buffers of find_wire_candidates: it allocates only while they grow.
struct WireSearchScratch {
  // The vote table is counted a direction at a time: three rows of offsets (the direction being
  // counted and its two predecessors, whose peaks it decides), all zero between calls.
  std::vector<std::uint16_t> rows;
  std::array<std::vector<std::uint32_t>, 3> full;  // each row's bins that reached min_points votes
  std::vector<std::uint64_t> cells;  // the eligible points' plan cells, sorted, each once
  std::vector<double> cell_x, cell_y;  // their centres from the aircraft
  std::vector<std::int32_t> cell_bin;  // their bins in the direction being counted (−1: none)
  std::vector<std::uint8_t> taken;
  std::vector<std::uint32_t> inliers;
  std::vector<double> offsets;
  std::vector<std::uint32_t> open;  // the eligible points not yet taken, by index …
  std::vector<double> open_e, open_n;  // … their plan offsets from the aircraft …
  std::vector<double> open_t;          // … and from the line of the peak being followed
  std::vector<std::uint32_t> near;  // a peak's open points near its line
};

// The wire candidates among the `points` with `eligible[p] != 0` (the others neither vote nor join
// a line), around the aircraft's plan position `aircraft_en`.
void find_wire_candidates(std::span<const ObstaclePoint> points,
                          std::span<const std::uint8_t> eligible, const Eigen::Vector2d& aircraft_en,
                          const DetectorParams& params, WireSearchScratch& scratch,
                          std::vector<WireCandidate>& out);

}  // namespace owsim
