#include "io/scenario/value_ranges.hpp"

#include <array>
#include <cmath>

#include "geometry/number_text.hpp"

namespace owsim {
namespace {

constexpr double kFar = kMaxOffsetFromOriginM;
constexpr double kLowestM = -1'000.0;   // below the Dead Sea shore, with the geoid
constexpr double kHighestM = 10'000.0;  // above any helicopter's ceiling

constexpr std::array kRanges = {
    // Any position: {e, n, u} in the local frame, or {lat, lon, h} on WGS-84.
    ValueRange{"<position>.e", -kFar, kFar, "m"},
    ValueRange{"<position>.n", -kFar, kFar, "m"},
    ValueRange{"<position>.u", kLowestM, kHighestM, "m"},
    ValueRange{"<position>.lat", -90.0, 90.0, "deg"},
    ValueRange{"<position>.lon", -180.0, 180.0, "deg"},
    ValueRange{"<position>.h", kLowestM, kHighestM, "m"},
    ValueRange{"origin.lat", -90.0, 90.0, "deg"},
    ValueRange{"origin.lon", -180.0, 180.0, "deg"},
    ValueRange{"origin.h", kLowestM, kHighestM, "m"},
    ValueRange{"sensor.mount.roll_deg", -360.0, 360.0, "deg"},
    ValueRange{"sensor.mount.pitch_deg", -360.0, 360.0, "deg"},
    ValueRange{"sensor.mount.yaw_deg", -360.0, 360.0, "deg"},
    ValueRange{"sensor.mount.lever_arm_m[]", -50.0, 50.0, "m"},
    ValueRange{"sensor.divergence_mrad", 0.0, 100.0, "mrad"},
    ValueRange{"sensor.beam_exit_radius_m", 0.0, 1.0, "m"},
    ValueRange{"sensor.threshold", 0.0, 1.0, ""},
    ValueRange{"sensor.range_noise_sigma_m", -1.0, 100.0, "m"},
    ValueRange{"sensor.min_return_separation_m", 0.0, 1'000.0, "m"},
    ValueRange{"sensor.prf_hz", 1.0, 1'000'000.0, "Hz"},
    ValueRange{"sensor.fibers_per_line", 2.0, 1'024.0, ""},
    ValueRange{"sensor.lines_per_frame", 1.0, 10'000.0, ""},
    ValueRange{"sensor.sweep_deg", 0.0, 180.0, "deg"},
    ValueRange{"sensor.sawtooth_deg", 0.0, 10.0, "deg"},
    ValueRange{"sensor.frame_jitter_deg", 0.0, 30.0, "deg"},
    ValueRange{"sensor.look_into_turn_s", 0.0, 60.0, "s"},
    ValueRange{"sensor.look_into_turn_limit_deg", 0.0, 90.0, "deg"},
    ValueRange{"sensor.alpha_table_deg[]", -90.0, 90.0, "deg"},
    ValueRange{"sensor.hellas_mirror_angle_factor_deg", 0.0, 10.0, "deg"},
    ValueRange{"sensor.counter.speed_of_light_mps", 2.9e8, 3.0e8, "m/s"},
    ValueRange{"sensor.counter.refractive_index_air", 1.0, 1.01, ""},
    ValueRange{"sensor.counter.timer_period_s", 1e-12, 1e-6, "s"},
    // SENSOR-SPEC §11: σ_1km in energy_rel units (the threshold's, at most 1); a pulse of 0.1 ns
    // to 1 µs; k_sun, k_sky variance ratios (calibrated near 1).
    ValueRange{"sensor.receiver.noise_at_1km", 0.0, 1.0, ""},
    ValueRange{"sensor.receiver.pulse_width_ns", 0.1, 1'000.0, "ns"},
    ValueRange{"sensor.receiver.sun_noise", 0.0, 1'000.0, ""},
    ValueRange{"sensor.receiver.sky_noise", 0.0, 1'000.0, ""},
    ValueRange{"atmosphere.transmission", 0.0, 1.0, ""},
    ValueRange{"atmosphere.visibility_km", 0.001, 1'000.0, "km"},
    ValueRange{"atmosphere.wavelength_um", 0.2, 20.0, "um"},
    ValueRange{"sun.elevation_deg", -90.0, 90.0, "deg"},  // any finite azimuth_deg, wrapped
    ValueRange{"trajectory.waypoints.speed_mps", 1.0, 150.0, "m/s"},
    ValueRange{"trajectory.waypoints.max_bank_deg", 1.0, 60.0, "deg"},
    ValueRange{"trajectory.tick_s", 1e-9, 1.0, "s"},
    ValueRange{"trajectory.magnetic_variation_deg", -180.0, 180.0, "deg"},
    ValueRange{"trajectory.start_s", 0.0, 1e10, "s"},
    ValueRange{"trajectory.duration_s", 0.0, 86'400.0, "s"},
    ValueRange{"scene.terrain.flat_u", kLowestM, kHighestM, "m"},
    ValueRange{"scene.terrain.reflectivity", 0.0, 1.0, ""},
    ValueRange{"scene.spans[].support_heights_m[]", 0.0, 1'000.0, "m"},
    ValueRange{"scene.spans[].lowest_point_m", -1'000.0, 1'000.0, "m"},
    ValueRange{"scene.spans[].layout[][]", -100.0, 100.0, "m"},
    ValueRange{"scene.spans[].conductor.diameter_mm", 1.0, 200.0, "mm"},
    ValueRange{"scene.spans[].conductor.reflectivity", 0.0, 1.0, ""},
    ValueRange{"scene.spans[].supports.diameter_m", 0.001, 20.0, "m"},
    ValueRange{"scene.spans[].supports.reflectivity", 0.0, 1.0, ""},
    ValueRange{"scene.poles[].height_m", 0.0, 1'000.0, "m"},
    ValueRange{"scene.poles[].diameter_m", 0.001, 20.0, "m"},
    ValueRange{"scene.poles[].reflectivity", 0.0, 1.0, ""},
    ValueRange{"scene.trees[].height_m", 0.0, 200.0, "m"},
    ValueRange{"scene.trees[].diameter_m", 0.001, 50.0, "m"},
    ValueRange{"scene.trees[].reflectivity", 0.0, 1.0, ""},
    ValueRange{"scene.forest.count", 0.0, 1'000'000.0, ""},
    ValueRange{"scene.forest.area.e[]", -kFar, kFar, "m"},
    ValueRange{"scene.forest.area.n[]", -kFar, kFar, "m"},
    ValueRange{"scene.forest.height_m[]", 0.0, 200.0, "m"},
    ValueRange{"scene.forest.diameter_m[]", 0.001, 50.0, "m"},
    ValueRange{"scene.forest.reflectivity", 0.0, 1.0, ""},
    // SENSOR-SPEC §10: κ of real fog lies near 0.02 sr⁻¹ (isotropic scattering: 1/4π); a fog's
    // visibility from a metre (no flight) to 100 km (no fog).
    ValueRange{"weather.backscatter_ratio_sr", 0.0, 1.0, "sr^-1"},
    ValueRange{"weather.fog[].visibility_m", 1.0, 100'000.0, "m"},
    ValueRange{"weather.fog[].layer.base_m", kLowestM, kHighestM, "m"},
    ValueRange{"weather.fog[].layer.top_m", kLowestM, kHighestM, "m"},
    ValueRange{"weather.fog[].box.e[]", -kFar, kFar, "m"},
    ValueRange{"weather.fog[].box.n[]", -kFar, kFar, "m"},
    ValueRange{"weather.fog[].box.u[]", kLowestM, kHighestM, "m"},
    // DETECTION-SPEC: the reference detector (detection/detector_params.cpp holds the same rows).
    ValueRange{"detector.window_s", 0.01, 60.0, "s"},
    ValueRange{"detector.hold_s", 0.0, 600.0, "s"},
    ValueRange{"detector.clearance_m", 0.0, 1'000.0, "m"},
    ValueRange{"detector.corridor_half_width_m", 0.1, 5'000.0, "m"},
    ValueRange{"detector.corridor_min_m", 0.0, 5'000.0, "m"},
    ValueRange{"detector.wire_min_aspect", 1.0, 1e6, ""},
    ValueRange{"detector.wire_isolation_m", 0.0, 100.0, "m"},
    ValueRange{"detector.wire_min_clearance_m", 0.0, 1'000.0, "m"},
    ValueRange{"detector.pole_min_height_m", 0.0, 1'000.0, "m"},
    ValueRange{"detector.pole_max_aspect", 0.001, 100.0, ""},
    ValueRange{"detector.pole_max_width_m", 0.01, 1'000.0, "m"},
    ValueRange{"detector.tree_min_height_m", 0.0, 1'000.0, "m"},
    ValueRange{"detector.tree_max_width_m", 0.01, 1'000.0, "m"},
    ValueRange{"detector.tree_isolation_widths", 0.0, 100.0, ""},
    ValueRange{"detector.standing_within_m", 0.0, 1'000.0, "m"},
    ValueRange{"detector.ground_cell_m", 0.5, 100.0, "m"},
    ValueRange{"detector.min_height_m", 0.01, 100.0, "m"},
    ValueRange{"detector.min_points", 2.0, 100'000.0, ""},
    ValueRange{"detector.wire_band_m", 0.01, 50.0, "m"},
    ValueRange{"detector.wire_gap_m", 0.01, 1'000.0, "m"},
    ValueRange{"detector.wire_gap_per_m", 0.0, 1.0, ""},
    ValueRange{"detector.wire_isolated_share", 0.0, 1.0, ""},
    ValueRange{"detector.link_m", 0.01, 100.0, "m"},
    ValueRange{"detector.link_per_m", 0.0, 1.0, ""},
    ValueRange{"detector.max_range_m", 1.0, 100'000.0, "m"},
};

// Whole numbers below 1e10 digit by digit (a count of 1000000000, not 1e+09); others to 9 digits.
std::string range_number_text(double value) {
  const bool whole = std::abs(value) < 1e10 && value == std::trunc(value);
  return number_text(value, whole ? 15 : 9);
}

}  // namespace

std::span<const ValueRange> value_ranges() { return kRanges; }

std::string key_pattern(std::string_view key_path) {
  std::string pattern;
  pattern.reserve(key_path.size());
  for (std::size_t i = 0; i < key_path.size(); ++i) {
    pattern += key_path[i];
    if (key_path[i] == '[') {
      while (i + 1 < key_path.size() && key_path[i + 1] != ']') ++i;
    }
  }
  return pattern;
}

const ValueRange* value_range_of(std::string_view key_path) {
  const std::string pattern = key_pattern(key_path);
  for (const ValueRange& range : kRanges) {
    if (range.key == pattern) return &range;
  }
  // A position's coordinate (waypoints, span ends, poles, trees: "scene.poles[].at.e").
  const std::size_t dot = pattern.rfind('.');
  if (dot == std::string::npos || pattern.starts_with("origin.")) return nullptr;
  const std::string position = "<position>" + pattern.substr(dot);
  for (const ValueRange& range : kRanges) {
    if (range.key == position) return &range;
  }
  return nullptr;
}

std::string out_of_range_problem(std::string_view key_path, double value) {
  const ValueRange* range = value_range_of(key_path);
  if (range == nullptr || (value >= range->min && value <= range->max)) return {};
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + string&&.
  std::string problem = "must be in [";
  problem.append(range_number_text(range->min)).append(", ");
  problem.append(range_number_text(range->max)).append("]");
  if (!range->unit.empty()) problem.append(" ").append(range->unit);
  return problem.append(", got ").append(range_number_text(value));
}

}  // namespace owsim
