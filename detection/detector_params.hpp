#pragma once
// The reference obstacle detector's parameters (DETECTION-SPEC §2–§4; the scenario's `detector:`
// section, INTERFACE.md "Obstacle warnings"). Every number the detector uses is here with its
// default: the spec's (window, hold, the source's class rules, the safety line's corridor) and the
// detector's own (ground cells, the least height and point count of an obstacle, how far apart a
// wire's points and a cluster's points may lie). docs/detection.md explains each.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace owsim {

struct DetectorParams {
  // DETECTION-SPEC §3: points accumulate over window_s; a track lives hold_s without support.
  double window_s = 1.0;
  double hold_s = 2.0;
  // §4, the safety line (the next stage reads them; validated here with the rest).
  double clearance_m = 15.0;
  double corridor_half_width_m = 50.0;
  double corridor_min_m = 10.0;

  // §2, the source's class rules (ch. 1).
  double wire_min_aspect = 20.0;      // WIRE: length / width >
  double wire_isolation_m = 5.0;      // WIRE: horizontal distance to other objects ≥
  double wire_min_clearance_m = 5.0;  // WIRE: height above the visible ground ≥
  double pole_min_height_m = 5.0;     // POLE: visible height >
  double pole_max_aspect = 0.2;       // POLE: width / height <
  double pole_max_width_m = 10.0;     // POLE: width (and length) <
  double tree_min_height_m = 3.0;     // TREE: visible height >
  double tree_max_width_m = 25.0;     // TREE: width ≤
  double tree_isolation_widths = 5.0;  // TREE: isolated from other objects by ≥ this × its width
  // An obstacle stands on the visible ground when its lowest point is within this of it; one that
  // does not (a piece of a wire, a bird, a cluster of false returns) is as high as its own points'
  // vertical extent, not as high as it floats.
  double standing_within_m = 5.0;

  // The detector's own.
  double ground_cell_m = 5.0;   // the ground map's cells: the visible ground is the lowest return
                                // in the 3×3 cells around a point
  double min_height_m = 1.0;    // a return at least this far above the visible ground is an
                                // obstacle's; lower ones are ground
  int min_points = 4;           // the fewest points an obstacle (and a wire) has
  double wire_band_m = 1.2;     // a wire's points lie within this of its line in plan
  double wire_gap_m = 15.0;     // the longest gap between a wire's points at short range …
  double wire_gap_per_m = 0.05;  // … and per metre of range beyond (a scan's gaps grow with range)
  double wire_isolated_share = 0.75;  // the share of a wire's points that must be isolated
  double link_m = 2.0;          // an obstacle's points join across this gap at short range …
  double link_per_m = 0.012;    // … and per metre of range beyond
  double max_range_m = 1500.0;  // points farther from the aircraft are not considered
};

// One key of a scenario's `detector:` section: its member and the closed range of its values
// (io/scenario/value_ranges.cpp holds the same rows as `detector.<name>`; a test keeps them equal).
struct DetectorKey {
  std::string_view name;
  double DetectorParams::*number = nullptr;  // null for min_points, the one integer
  double min;
  double max;
  std::string_view unit;
};
[[nodiscard]] std::span<const DetectorKey> detector_keys();

// What is wrong with `params`, each as "<key>: must be in [min, max] <unit>, got <value>"; empty
// when every value lies in its range.
[[nodiscard]] std::vector<std::string> detector_param_problems(const DetectorParams& params);

}  // namespace owsim
