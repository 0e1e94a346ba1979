#include "io/report/report_frames.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/error.hpp"
#include "geometry/scene.hpp"
#include "sensor/fiber_layout.hpp"

namespace owsim {
namespace {

// The mark's priority: wire, pole, tree, fog, then a false first return (noise); nothing else is
// marked.
int mark_rank(std::uint8_t surface, int return_number) {
  switch (static_cast<SurfaceClass>(surface)) {
    case SurfaceClass::wire:
      return 0;
    case SurfaceClass::pole:
      return 1;
    case SurfaceClass::tree:
      return 2;
    case SurfaceClass::fog:
      return 3;
    case SurfaceClass::noise:
      return return_number == 1 ? 4 : 99;
    default:
      return 99;
  }
}

}  // namespace

RangeImageLayout range_image_layout(const ScanParams& scan) {
  RangeImageLayout layout;
  layout.lines = scan.lines_per_frame;
  layout.fibers = fibers_top_down(scan);
  layout.row_of_fiber.assign(static_cast<std::size_t>(scan.fibers_per_line) + 1, -1);
  for (std::size_t row = 0; row < layout.fibers.size(); ++row) {
    layout.alpha_deg.push_back(fiber_alpha_deg(scan, layout.fibers[row]));
    layout.row_of_fiber[static_cast<std::size_t>(layout.fibers[row])] = static_cast<int>(row);
  }
  layout.beta_first_deg = -scan.sweep_deg / 2;
  layout.beta_last_deg = scan.sweep_deg / 2;
  return layout;
}

ReportFrames report_frames(const ReportPoints& points, const RangeImageLayout& layout,
                           std::int64_t frames_total_hint, int max_frames) {
  if (max_frames < 1) throw input_error("--max-frames", std::to_string(max_frames) + " < 1");
  ReportFrames out;
  std::int64_t last_frame = -1;
  for (const std::int32_t frame : points.frame)
    last_frame = std::max<std::int64_t>(last_frame, frame);
  out.frames_total = std::max(frames_total_hint, last_frame + 1);
  const std::int64_t shown = std::min<std::int64_t>(out.frames_total, max_frames);
  for (std::int64_t i = 0; i < shown; ++i) out.frames.push_back(i * out.frames_total / shown);
  // Frame f is shown in slot i when ⌊i · total / shown⌋ = f; slots are at least a frame apart
  // (total ≥ shown), so the only candidate is i = ⌈f · shown / total⌉. No table sized by the
  // frame count (frames and shown below 2^31: the products stay below 2^62).
  const auto slot_of_frame = [&](std::int64_t frame) -> std::int64_t {
    const std::int64_t i = (frame * shown + out.frames_total - 1) / out.frames_total;
    return i < shown && i * out.frames_total / shown == frame ? i : -1;
  };
  const std::size_t rows = layout.fibers.size();
  const auto lines = static_cast<std::size_t>(layout.lines);
  const std::size_t cells = rows * lines;
  const std::size_t frame_bytes = 3 * cells;
  out.planes.assign(static_cast<std::size_t>(shown) * frame_bytes, 0);
  std::vector<std::uint8_t> rank(static_cast<std::size_t>(shown) * cells, 99);
  for (std::size_t i = 0; i < points.frame.size(); ++i) {
    const std::int64_t slot = slot_of_frame(points.frame[i]);
    if (slot < 0) continue;
    const int fiber = points.fiber[i], line = points.line[i];
    const int row = fiber >= 0 && fiber < static_cast<int>(layout.row_of_fiber.size())
                        ? layout.row_of_fiber[static_cast<std::size_t>(fiber)]
                        : -1;
    if (row < 0 || line < 0 || line >= layout.lines) {
      ++out.returns_outside;
      continue;
    }
    const int column = points.frame[i] % 2 == 0 ? line : layout.lines - 1 - line;
    const std::size_t cell =
        static_cast<std::size_t>(row) * lines + static_cast<std::size_t>(column);
    std::uint8_t* plane = out.planes.data() + static_cast<std::size_t>(slot) * frame_bytes;
    if (points.return_number[i] == 1) {
      const std::uint16_t dm = range_decimetres(points.range_m[i]);
      plane[2 * cell] = static_cast<std::uint8_t>(dm & 0xFF);
      plane[2 * cell + 1] = static_cast<std::uint8_t>(dm >> 8);
    }
    const int r = mark_rank(points.surface[i], points.return_number[i]);
    std::uint8_t& best = rank[static_cast<std::size_t>(slot) * cells + cell];
    if (r < best) {
      best = static_cast<std::uint8_t>(r);
      plane[2 * cells + cell] = static_cast<std::uint8_t>(points.surface[i] + 1);
    }
  }
  return out;
}

}  // namespace owsim
