#include "detection/detector_params.hpp"

#include <array>
#include <cmath>

#include "geometry/number_text.hpp"

namespace owsim {
namespace {

using P = DetectorParams;
constexpr std::array kKeys{
    DetectorKey{"window_s", &P::window_s, 0.01, 60.0, "s"},
    DetectorKey{"hold_s", &P::hold_s, 0.0, 600.0, "s"},
    DetectorKey{"clearance_m", &P::clearance_m, 0.0, 1'000.0, "m"},
    DetectorKey{"corridor_half_width_m", &P::corridor_half_width_m, 0.1, 5'000.0, "m"},
    DetectorKey{"corridor_min_m", &P::corridor_min_m, 0.0, 5'000.0, "m"},
    DetectorKey{"wire_min_aspect", &P::wire_min_aspect, 1.0, 1e6, ""},
    DetectorKey{"wire_isolation_m", &P::wire_isolation_m, 0.0, 100.0, "m"},
    DetectorKey{"wire_min_clearance_m", &P::wire_min_clearance_m, 0.0, 1'000.0, "m"},
    DetectorKey{"pole_min_height_m", &P::pole_min_height_m, 0.0, 1'000.0, "m"},
    DetectorKey{"pole_max_aspect", &P::pole_max_aspect, 0.001, 100.0, ""},
    DetectorKey{"pole_max_width_m", &P::pole_max_width_m, 0.01, 1'000.0, "m"},
    DetectorKey{"tree_min_height_m", &P::tree_min_height_m, 0.0, 1'000.0, "m"},
    DetectorKey{"tree_max_width_m", &P::tree_max_width_m, 0.01, 1'000.0, "m"},
    DetectorKey{"tree_isolation_widths", &P::tree_isolation_widths, 0.0, 100.0, ""},
    DetectorKey{"standing_within_m", &P::standing_within_m, 0.0, 1'000.0, "m"},
    DetectorKey{"ground_cell_m", &P::ground_cell_m, 0.5, 100.0, "m"},
    DetectorKey{"min_height_m", &P::min_height_m, 0.01, 100.0, "m"},
    DetectorKey{"min_points", nullptr, 2.0, 100'000.0, ""},
    DetectorKey{"wire_band_m", &P::wire_band_m, 0.01, 50.0, "m"},
    DetectorKey{"wire_gap_m", &P::wire_gap_m, 0.01, 1'000.0, "m"},
    DetectorKey{"wire_gap_per_m", &P::wire_gap_per_m, 0.0, 1.0, ""},
    DetectorKey{"wire_isolated_share", &P::wire_isolated_share, 0.0, 1.0, ""},
    DetectorKey{"link_m", &P::link_m, 0.01, 100.0, "m"},
    DetectorKey{"link_per_m", &P::link_per_m, 0.0, 1.0, ""},
    DetectorKey{"max_range_m", &P::max_range_m, 1.0, 100'000.0, "m"},
};

}  // namespace

std::span<const DetectorKey> detector_keys() { return kKeys; }

std::vector<std::string> detector_param_problems(const DetectorParams& params) {
  std::vector<std::string> problems;
  for (const DetectorKey& key : kKeys) {
    const double value =
        key.number != nullptr ? params.*key.number : static_cast<double>(params.min_points);
    if (std::isfinite(value) && value >= key.min && value <= key.max) continue;
    std::string problem = std::string(key.name) + ": must be in [" + number_text(key.min, 15) +
                          ", " + number_text(key.max, 15) + "]";
    if (!key.unit.empty()) {
      problem += ' ';
      problem += key.unit;
    }
    problem += ", got ";
    problem += number_text(value);
    problems.push_back(problem);
  }
  return problems;
}

}  // namespace owsim
