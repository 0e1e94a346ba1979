#pragma once
// The frame player's range images for `owsim view`: for each shown frame, one cell per pulse laid
// out as the quick-look PNGs are (io/images/quicklook.hpp): rows = the ranging fibers top to
// bottom by α (fibers_top_down), columns = lines in β order (line l is column l on frames
// sweeping up, the even frames, and column lines−1−l on frames sweeping down). A cell holds the
// first return's range in decimetres (0: no return; 1..65535) and a mark: 1 + the SurfaceClass of
// the pulse's wire, pole, tree or fog return if any (wire before pole before tree before fog, so a
// wire behind a nearer tree still shows), else of its first return if that is a false return
// (noise, as the quick-look range images colour it), 0 otherwise.
//
// A long flight shows at most max_frames frames, evenly spread: frame ⌊i·total/max_frames⌋.
#include <cstdint>
#include <vector>

#include "io/report/report_points.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

struct RangeImageLayout {
  int lines = 0;                  // columns
  std::vector<int> fibers;        // the fiber of each row, top to bottom
  std::vector<double> alpha_deg;  // α of each row
  std::vector<int> row_of_fiber;  // by fiber 0..fibers_per_line; −1: no row
  double beta_first_deg = 0.0;    // nominal mirror β of column 0 (the sweep start)
  double beta_last_deg = 0.0;     // of the last column
};

[[nodiscard]] RangeImageLayout range_image_layout(const ScanParams& scan);

struct ReportFrames {
  std::int64_t frames_total = 0;     // frames of the flight (the highest frame seen + 1, or more)
  std::vector<std::int64_t> frames;  // the frames shown, ascending
  // Per shown frame, rows × lines cells: the ranges (uint16, little-endian) then the marks.
  std::vector<std::uint8_t> planes;
  std::uint64_t returns_outside = 0;  // returns whose line or fiber the layout has no cell for
};

// Needs points.pulses_known. frames_total_hint: the flight's frame count if known (summary.json),
// else 0. Throws owsim::Error if max_frames < 1.
[[nodiscard]] ReportFrames report_frames(const ReportPoints& points, const RangeImageLayout& layout,
                                         std::int64_t frames_total_hint, int max_frames);

}  // namespace owsim
