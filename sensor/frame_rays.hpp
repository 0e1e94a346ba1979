#pragma once
// The pulses of a frame and the central ray of each, built a line at a time for a few nanoseconds
// a pulse (SENSOR-SPEC §2 scan pattern, §4 frames, §5 pose at each pulse's time): what the frame
// simulator traces.
//
// Pulses are exactly pulse_of_frame's (the slot's fiber, α and β_FC come from a table made once).
//
// Rays. The exact placement (sensor_placement of the pose at the pulse's own time) is taken at
// three pulses of each line: its first, its middle one (slot F/2, F = fibers per line) and the
// first of the next line. In between, every entry of enu_from_src and of the origin follows the
// quadratic through those three, in s = slot / F; a line lasts F / PRF = 2.09 ms. Within a spline
// interval the error is about (h/2)³/(9√3) · |d³R/dt³| (h the line duration); a line that
// crosses a trajectory knot, where the spline's third derivative jumps, errs more. Measured
// against the per-pulse reference (pulse_ray below) in tests/test_frame_rays.cpp, with a tilted
// mount and a 2.6 m lever arm: at most 4.4e-8 rad and 0.2 µm on the corridor's planned turns,
// 7e-9 rad on the real recorded flight, 4e-9 rad through a 90°/s turn with 141°/s roll swings;
// the test holds them to 1e-7 rad and 1e-6 m (0.1 mm at the 1.2 km timeout range, 1e-4 of the
// beam's 1 mrad divergence). Slots 0 and F/2 get the exact placement, to rounding.
// β of each pulse: by angle addition from the line's first mirror β and the slot's offset (mirror
// advance within the line + β_FC), exact to a few ulp. Written as a·u + b·v + sin α·e_y (see
// SlotRays), the blended rotation is applied per line to u, v and e_y, and the per-pulse work is
// three quadratics and a weighted sum per component over arrays the compiler vectorises.
// Thread-safe (const); allocation-free after construction.
#include <cstdint>
#include <span>
#include <vector>

#include "sensor/mounting.hpp"
#include "sensor/pose_source.hpp"
#include "sensor/pulse_candidates.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

// The per-pulse reference: the pose at the pulse's time, its placement and the ray through α, β
// (SENSOR-SPEC §4, §5). The reference fiber has no ray (a default PulseRay).
[[nodiscard]] PulseRay pulse_ray(const Pulse& pulse, const PoseSource& poses, const Mount& mount,
                                 SensorModel model);

class FrameRayBuilder {
 public:
  // Throws owsim::Error for scan parameters that fail validate().
  FrameRayBuilder(const ScanParams& scan, const Mount& mount);

  // Pulses and rays of lines [line_begin, line_end) of the frame into spans holding exactly those
  // lines' pulses (entry (line − line_begin) · F + slot); active = 0 for the reference fiber, whose
  // ray is left default.
  void build_lines(const FrameSweep& sweep, const PoseSource& poses, int line_begin, int line_end,
                   std::span<Pulse> pulses, std::span<PulseRay> rays,
                   std::span<std::uint8_t> active) const;

 private:
  struct Slot {
    int fiber = 0;
    bool reference = false;
    double alpha_deg = 0;
    double sawtooth_deg = 0;
  };
  // The SRC ray of every slot as a·u + b·v + sin α·e_y, where u = (cos β_L, 0, sin β_L) and
  // v = (−sin β_L, 0, cos β_L) depend only on the line's first mirror β_L: a = cos α cos δ,
  // b = cos α sin δ, δ the slot's offset from β_L (by direction +1 / −1, index 0 / 1). Arrays by
  // slot, so the per-pulse arithmetic runs over plain arrays of doubles.
  struct SlotRays {
    std::vector<double> a[2], b[2], sin_alpha;
    std::vector<double> s;     // slot / F, the blend parameter
    std::vector<double> slot;  // the slot index as a double
  };

  [[nodiscard]] SensorPlacement placement_at(const PoseSource& poses, double time_s) const;

  ScanParams scan_;
  Eigen::Matrix3d body_from_src_;  // R_mount · R_model
  Eigen::Vector3d lever_arm_m_;
  std::vector<Slot> slots_;
  SlotRays slot_rays_;
};

}  // namespace owsim
