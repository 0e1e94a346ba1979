#pragma once
// The linear fiber array of one scan line (SENSOR-SPEC §2, table 1): which fiber fires in each
// slot of a line, the across-line angle α of each fiber, and the sawtooth fine correction β_FC.
//
// Default layout for 128 fibers: fibers 1..64 look from the left edge (α = −21°) to the centre
// (0°), fibers 65..127 from the right edge (+21°) to the centre (0°), linear within each half
// (steps 21/63° and 21/62°, SENSOR-SPEC §2 decision); fiber 128 is the internal reference fiber
// and has no α (NaN). ScanParams::alpha_table_deg, when not empty, replaces the default table.
// Valid for fibers_per_line ≥ 2; α is exact to double rounding.
#include <vector>

#include "sensor/scan_params.hpp"

namespace owsim {

inline constexpr double kFiberEdgeAlphaDeg = 21.0;  // §2 table 1: |α| of fibers 1 and 65

// Fibers in the left half of the array (1..n): fibers_per_line / 2, 64 of 128  (SENSOR-SPEC §2)
[[nodiscard]] constexpr int left_half_fibers(int fibers_per_line) { return fibers_per_line / 2; }

// True for the last fiber of the line, the internal reference fiber  (SENSOR-SPEC §2)
[[nodiscard]] bool is_reference_fiber(const ScanParams& p, int fiber);

// The fiber (1..fibers_per_line) that fires in slot 0..fibers_per_line−1 of a line (SENSOR-SPEC
// §2). crosstalk_resorted: slot s → fiber s+1. sequential: left to right (1..64, 127, 126, …, 65),
// then the reference fiber. Throws owsim::Error for a slot outside the line.
[[nodiscard]] int fiber_at_slot(const ScanParams& p, int slot);
// The inverse of fiber_at_slot  (SENSOR-SPEC §2)
[[nodiscard]] int slot_of_fiber(const ScanParams& p, int fiber);

// Default α table (SENSOR-SPEC §2, table 1) for fibers 1..fibers_per_line−1, degrees: the left
// half −21°→0°, the right half +21°→0°, linear within each half (a half of one fiber sits at its
// edge, ±21°).
[[nodiscard]] std::vector<double> default_alpha_table_deg(int fibers_per_line);
// α of one fiber in degrees, from ScanParams::alpha_table_deg or the default table; NaN for the
// reference fiber  (SENSOR-SPEC §2, table 1). Throws for a wrong-sized table or a bad fiber.
[[nodiscard]] double fiber_alpha_deg(const ScanParams& p, int fiber);

// The ranging fibers (the reference fiber left out) as the sensor sees them from top to bottom:
// sorted by α, highest first, equal α in fiber order (for MilOWS α is up, SENSOR-SPEC §4 pinned
// conventions: fiber 64 above 127). The rows of a range image (quick-look PNG, `owsim view`).
[[nodiscard]] std::vector<int> fibers_top_down(const ScanParams& p);

// Sawtooth fine correction β_FC: −sawtooth on odd fibers, +sawtooth on even  (SENSOR-SPEC §2,
// eq 4.3)
[[nodiscard]] double sawtooth_deg(const ScanParams& p, int fiber);

}  // namespace owsim
