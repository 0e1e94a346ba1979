#include "sensor/frame_rays.hpp"

#include <cmath>
#include <numbers>

#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/motor_encoder.hpp"
#include "sensor/scan_params_check.hpp"

namespace owsim {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// P(s) = p0 + s · (p1 + s · p2): the quadratic through the values at s = 0, 1/2 and 1.
template <typename Value>
struct Quadratic {
  Value p0, p1, p2;

  Quadratic(const Value& at_0, const Value& at_half, const Value& at_1)
      : p0(at_0),
        p1(4.0 * at_half - 3.0 * at_0 - at_1),
        p2(2.0 * at_0 - 4.0 * at_half + 2.0 * at_1) {}
};

}  // namespace

PulseRay pulse_ray(const Pulse& pulse, const PoseSource& poses, const Mount& mount,
                   SensorModel model) {
  if (pulse.reference) return PulseRay{};
  const SensorPlacement placement = sensor_placement(poses.pose_at(pulse.time_s), mount, model);
  return PulseRay{placement.origin_enu_m,
                  ray_direction_enu(placement, pulse.alpha_deg, pulse.beta_deg)};
}

FrameRayBuilder::FrameRayBuilder(const ScanParams& scan, const Mount& mount)
    : scan_(scan),
      body_from_src_(mount_rotation(mount) * model_rotation(scan.model)),
      lever_arm_m_(mount.lever_arm_m) {
  validate(scan_);
  const int pulses = scan_.pulses_per_frame();
  slots_.resize(static_cast<std::size_t>(scan_.fibers_per_line));
  for (int index = 0; index < scan_.fibers_per_line; ++index) {
    Slot& slot = slots_[static_cast<std::size_t>(index)];
    slot.fiber = fiber_at_slot(scan_, index);
    slot.reference = is_reference_fiber(scan_, slot.fiber);
    slot.alpha_deg = fiber_alpha_deg(scan_, slot.fiber);
    slot.sawtooth_deg = sawtooth_deg(scan_, slot.fiber);
    if (slot.reference) continue;
    slot.sin_alpha = std::sin(slot.alpha_deg * kRadPerDeg);
    slot.cos_alpha = std::cos(slot.alpha_deg * kRadPerDeg);
    for (const int direction : {1, -1}) {
      const double offset_deg = direction * scan_.sweep_deg * index / pulses + slot.sawtooth_deg;
      const std::size_t d = direction > 0 ? 0 : 1;
      slot.sin_offset[d] = std::sin(offset_deg * kRadPerDeg);
      slot.cos_offset[d] = std::cos(offset_deg * kRadPerDeg);
    }
  }
}

SensorPlacement FrameRayBuilder::placement_at(const PoseSource& poses, double time_s) const {
  return sensor_placement(poses.pose_at(time_s), body_from_src_, lever_arm_m_);
}

void FrameRayBuilder::build_lines(const FrameSweep& sweep, const PoseSource& poses, int line_begin,
                                  int line_end, std::span<Pulse> pulses, std::span<PulseRay> rays,
                                  std::span<std::uint8_t> active) const {
  const int fibers = scan_.fibers_per_line;
  const int frame_pulses = scan_.pulses_per_frame();
  if (line_begin < 0 || line_end > scan_.lines_per_frame || line_begin > line_end ||
      pulses.size() != static_cast<std::size_t>(frame_pulses) || rays.size() != pulses.size() ||
      active.size() != pulses.size()) {
    throw Error("frame rays: lines or buffers do not fit the frame");
  }
  const std::size_t direction = sweep.direction > 0 ? 0 : 1;
  const int mov_dir = sweep.direction > 0 ? 0 : 1;
  const bool milows = scan_.model == SensorModel::milows;
  const double slot_step = 1.0 / fibers;

  SensorPlacement start =
      placement_at(poses, pulse_time_s(scan_, sweep.frame, line_begin * fibers));
  for (int line = line_begin; line < line_end; ++line) {
    const int first = line * fibers;
    const SensorPlacement middle =
        placement_at(poses, pulse_time_s(scan_, sweep.frame, first + fibers / 2));
    const SensorPlacement end =
        placement_at(poses, pulse_time_s(scan_, sweep.frame, first + fibers));
    const Quadratic<Eigen::Matrix3d> rotation(start.enu_from_src, middle.enu_from_src,
                                              end.enu_from_src);
    const Quadratic<Eigen::Vector3d> origin(start.origin_enu_m, middle.origin_enu_m,
                                            end.origin_enu_m);
    const double line_beta = mirror_beta_deg(scan_, sweep, first) * kRadPerDeg;
    const double sin_line = std::sin(line_beta), cos_line = std::cos(line_beta);

    for (int index = 0; index < fibers; ++index) {
      const Slot& slot = slots_[static_cast<std::size_t>(index)];
      const int k = first + index;
      const auto at = static_cast<std::size_t>(k);
      Pulse& pulse = pulses[at];
      pulse.index = k;
      pulse.line = line;
      pulse.slot = index;
      pulse.fiber = slot.fiber;
      pulse.reference = slot.reference;
      pulse.time_s = pulse_time_s(scan_, sweep.frame, k);
      pulse.alpha_deg = slot.alpha_deg;
      pulse.mirror_beta_deg = mirror_beta_deg(scan_, sweep, k);
      pulse.beta_deg = pulse.mirror_beta_deg + slot.sawtooth_deg;
      pulse.encoder = milows ? encoder_from_mirror_beta(pulse.mirror_beta_deg) : 0;
      pulse.frame_gate = k == frame_pulses - 1;
      pulse.line_gate = index == fibers - 1;
      pulse.mov_dir = mov_dir;
      if (slot.reference) {
        active[at] = 0;
        rays[at] = PulseRay{};
        continue;
      }
      // β = line β + offset; SRC ray (cos α cos β, sin α, cos α sin β)  (SENSOR-SPEC §4)
      const double sin_beta =
          sin_line * slot.cos_offset[direction] + cos_line * slot.sin_offset[direction];
      const double cos_beta =
          cos_line * slot.cos_offset[direction] - sin_line * slot.sin_offset[direction];
      const Eigen::Vector3d src(slot.cos_alpha * cos_beta, slot.sin_alpha,
                                slot.cos_alpha * sin_beta);
      const double s = index * slot_step;
      const Eigen::Vector3d dir =
          rotation.p0 * src + s * (rotation.p1 * src + s * (rotation.p2 * src));
      active[at] = 1;
      rays[at] = PulseRay{origin.p0 + s * (origin.p1 + s * origin.p2), dir / dir.norm()};
    }
    start = end;
  }
}

}  // namespace owsim
