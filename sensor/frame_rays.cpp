#include "sensor/frame_rays.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/error.hpp"
#include "geometry/exact_round.hpp"
#include "geometry/vector_clones.hpp"
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

// The chunk arithmetic below is compiled for AVX2 as well (geometry/vector_clones.hpp).

constexpr int kMaxChunk = 64;

// A chunk of a line's slots: the per-slot tables from its first slot, and the line's scalars.
struct LineChunk {
  int n = 0;
  const double* slot = nullptr;  // the slot index as a double
  const double* a = nullptr;
  const double* b = nullptr;
  const double* sin_alpha = nullptr;
  const double* blend = nullptr;  // s = slot / F
  bool time_from_index = false;   // the line's first flight index is a double exactly
  bool milows = false;
  double start_s = 0, prf_hz = 0, line_index = 0;                                // time
  double beta_start_deg = 0, signed_sweep_deg = 0, first = 0, frame_pulses = 0;  // mirror β
  double u[3][3] = {}, v[3][3] = {}, w[3][3] = {}, o[3][3] = {};                 // [j][component]
};

struct ChunkArrays {
  alignas(64) double dir[3][kMaxChunk];
  alignas(64) double org[3][kMaxChunk];
  alignas(64) double time_s[kMaxChunk];
  alignas(64) double mirror_beta[kMaxChunk];
  alignas(64) double counts[kMaxChunk];          // φ / count size (MilOWS)
  alignas(64) double rounded_counts[kMaxChunk];  // round_half_away_in_lanes(counts)
};

// The chunk's per-pulse arithmetic over arrays: time (when time_from_index), mirror β, the
// encoder's φ in counts, and the unit direction and origin of each ray (the reference slot's zero
// vector becomes NaN here and is not stored).
OWSIM_VECTOR_CLONES void chunk_arithmetic(const LineChunk& line, ChunkArrays& out) {
  const int n = line.n;
  if (line.time_from_index) {
    for (int i = 0; i < n; ++i) {
      out.time_s[i] = line.start_s + (line.line_index + line.slot[i]) / line.prf_hz;
    }
  }
  for (int i = 0; i < n; ++i) {
    out.mirror_beta[i] = line.beta_start_deg +
                         line.signed_sweep_deg * (line.first + line.slot[i]) / line.frame_pulses;
  }
  if (line.milows) {
    for (int i = 0; i < n; ++i) {
      out.counts[i] = motor_angle_deg(out.mirror_beta[i]) / kEncoderDegPerCount;
    }
    for (int i = 0; i < n; ++i) out.rounded_counts[i] = round_half_away_in_lanes(out.counts[i]);
  }
  for (int c = 0; c < 3; ++c) {
    const double u0 = line.u[0][c], u1 = line.u[1][c], u2 = line.u[2][c];
    const double v0 = line.v[0][c], v1 = line.v[1][c], v2 = line.v[2][c];
    const double w0 = line.w[0][c], w1 = line.w[1][c], w2 = line.w[2][c];
    const double o0 = line.o[0][c], o1 = line.o[1][c], o2 = line.o[2][c];
    for (int i = 0; i < n; ++i) {
      const double s = line.blend[i];
      out.dir[c][i] = line.a[i] * (u0 + s * (u1 + s * u2)) + line.b[i] * (v0 + s * (v1 + s * v2)) +
                      line.sin_alpha[i] * (w0 + s * (w1 + s * w2));
      out.org[c][i] = o0 + s * (o1 + s * o2);
    }
  }
  for (int i = 0; i < n; ++i) {
    const double inverse_norm =
        1.0 / std::sqrt(out.dir[0][i] * out.dir[0][i] + out.dir[1][i] * out.dir[1][i] +
                        out.dir[2][i] * out.dir[2][i]);
    for (int c = 0; c < 3; ++c) out.dir[c][i] *= inverse_norm;
  }
}

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
  const auto fibers = static_cast<std::size_t>(scan_.fibers_per_line);
  slots_.resize(fibers);
  for (std::vector<double>* column :
       {&slot_rays_.a[0], &slot_rays_.a[1], &slot_rays_.b[0], &slot_rays_.b[1],
        &slot_rays_.sin_alpha, &slot_rays_.s, &slot_rays_.slot}) {
    column->assign(fibers, 0.0);
  }
  for (std::size_t index = 0; index < fibers; ++index) {
    Slot& slot = slots_[index];
    const int i = static_cast<int>(index);
    slot.fiber = fiber_at_slot(scan_, i);
    slot.reference = is_reference_fiber(scan_, slot.fiber);
    slot.alpha_deg = fiber_alpha_deg(scan_, slot.fiber);
    slot.sawtooth_deg = sawtooth_deg(scan_, slot.fiber);
    slot_rays_.s[index] = static_cast<double>(i) / scan_.fibers_per_line;
    slot_rays_.slot[index] = static_cast<double>(i);
    if (slot.reference) continue;
    const double cos_alpha = std::cos(slot.alpha_deg * kRadPerDeg);
    slot_rays_.sin_alpha[index] = std::sin(slot.alpha_deg * kRadPerDeg);
    for (const int direction : {1, -1}) {
      const double offset_deg = direction * scan_.sweep_deg * i / pulses + slot.sawtooth_deg;
      const std::size_t d = direction > 0 ? 0 : 1;
      slot_rays_.a[d][index] = cos_alpha * std::cos(offset_deg * kRadPerDeg);
      slot_rays_.b[d][index] = cos_alpha * std::sin(offset_deg * kRadPerDeg);
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
      pulses.size() != static_cast<std::size_t>((line_end - line_begin) * fibers) ||
      rays.size() != pulses.size() || active.size() != pulses.size()) {
    throw Error("frame rays: lines or buffers do not fit the frame");
  }
  const std::size_t direction = sweep.direction > 0 ? 0 : 1;
  const int mov_dir = sweep.direction > 0 ? 0 : 1;
  const bool milows = scan_.model == SensorModel::milows;

  // Per-pulse time, mirror β and encoder word by pulse_time_s's, mirror_beta_deg's and
  // encoder_from_mirror_beta's own expressions, over arrays. The pulse index k in the frame is
  // the line's first plus the slot, exactly; the flight's index f·P + k is formed the same way
  // where that gives pulse_time_s's double (below), else each pulse is timed by pulse_time_s.
  const std::int64_t frame_first = sweep.frame * static_cast<std::int64_t>(frame_pulses);
  LineChunk line_chunk;
  line_chunk.milows = milows;
  line_chunk.start_s = scan_.start_s;
  line_chunk.prf_hz = scan_.prf_hz;
  line_chunk.beta_start_deg = sweep.mirror_beta_start_deg;
  line_chunk.signed_sweep_deg = sweep.direction * scan_.sweep_deg;
  line_chunk.frame_pulses = static_cast<double>(frame_pulses);
  ChunkArrays arrays;
  const double(&dir)[3][kMaxChunk] = arrays.dir;
  const double(&org)[3][kMaxChunk] = arrays.org;
  const double* const time_s = arrays.time_s;
  const double* const mirror_beta = arrays.mirror_beta;
  const double* const counts = arrays.counts;
  const double* const rounded_counts = arrays.rounded_counts;

  // A line's rays: dir(s) = R(s) · (a·u + b·v + sin α·e_y) with R(s) = R0 + s·R1 + s²·R2, so
  // dir(s) = a·U(s) + b·V(s) + sin α·W(s), U(s) = R(s)·u and so on: per line, the nine vectors
  // Rj·u, Rj·v, Rj·e_y; per pulse, three quadratics and a weighted sum in each component, over
  // arrays of the line's slots (chunk_arithmetic).
  SensorPlacement start =
      placement_at(poses, pulse_time_s(scan_, sweep.frame, line_begin * fibers));
  for (int line = line_begin; line < line_end; ++line) {
    const int first = line * fibers;
    const SensorPlacement middle =
        placement_at(poses, pulse_time_s(scan_, sweep.frame, first + fibers / 2));
    // pulse_time_s throws if the line's last index overflows int64; so every index below fits.
    const SensorPlacement end =
        placement_at(poses, pulse_time_s(scan_, sweep.frame, first + fibers));
    const Quadratic<Eigen::Matrix3d> rotation(start.enu_from_src, middle.enu_from_src,
                                              end.enu_from_src);
    const Quadratic<Eigen::Vector3d> origin(start.origin_enu_m, middle.origin_enu_m,
                                            end.origin_enu_m);
    const double line_beta = mirror_beta_deg(scan_, sweep, first) * kRadPerDeg;
    const double sin_line = std::sin(line_beta), cos_line = std::cos(line_beta);
    const Eigen::Matrix3d* const r[3] = {&rotation.p0, &rotation.p1, &rotation.p2};
    const Eigen::Vector3d* const o[3] = {&origin.p0, &origin.p1, &origin.p2};
    for (int j = 0; j < 3; ++j) {
      for (int c = 0; c < 3; ++c) {
        const Eigen::Matrix3d& m = *r[j];
        line_chunk.u[j][c] = cos_line * m(c, 0) + sin_line * m(c, 2);
        line_chunk.v[j][c] = cos_line * m(c, 2) - sin_line * m(c, 0);
        line_chunk.w[j][c] = m(c, 1);
        line_chunk.o[j][c] = (*o[j])(c);
      }
    }
    const std::int64_t line_index = frame_first + first;
    const auto line_index_d = static_cast<double>(line_index);
    // When the line's first index is a double exactly, the double sum with the slot is rounded
    // once, as the conversion of the int64 index is: the same time.
    line_chunk.time_from_index =
        std::abs(line_index_d) < 0x1p62 && static_cast<std::int64_t>(line_index_d) == line_index;
    line_chunk.line_index = line_index_d;
    line_chunk.first = static_cast<double>(first);

    for (int chunk = 0; chunk < fibers; chunk += kMaxChunk) {
      const int n = std::min(kMaxChunk, fibers - chunk);
      const auto at_chunk = static_cast<std::size_t>(chunk);
      line_chunk.n = n;
      line_chunk.slot = slot_rays_.slot.data() + at_chunk;
      line_chunk.a = slot_rays_.a[direction].data() + at_chunk;
      line_chunk.b = slot_rays_.b[direction].data() + at_chunk;
      line_chunk.sin_alpha = slot_rays_.sin_alpha.data() + at_chunk;
      line_chunk.blend = slot_rays_.s.data() + at_chunk;
      chunk_arithmetic(line_chunk, arrays);
      if (!line_chunk.time_from_index) {
        for (int i = 0; i < n; ++i) {
          arrays.time_s[i] = pulse_time_s(scan_, sweep.frame, first + chunk + i);
        }
      }
      for (int i = 0; i < n; ++i) {
        const int index = chunk + i;
        const Slot& slot = slots_[static_cast<std::size_t>(index)];
        const int k = first + index;
        const auto at = static_cast<std::size_t>(k - line_begin * fibers);
        Pulse& pulse = pulses[at];
        pulse.index = k;
        pulse.line = line;
        pulse.slot = index;
        pulse.fiber = slot.fiber;
        pulse.reference = slot.reference;
        pulse.time_s = time_s[i];
        pulse.alpha_deg = slot.alpha_deg;
        pulse.mirror_beta_deg = mirror_beta[i];
        pulse.beta_deg = mirror_beta[i] + slot.sawtooth_deg;
        pulse.encoder = milows ? encoder_word(counts[i], rounded_counts[i]) : 0;
        pulse.frame_gate = k == frame_pulses - 1;
        pulse.line_gate = index == fibers - 1;
        pulse.mov_dir = mov_dir;
        if (slot.reference) {
          active[at] = 0;
          rays[at] = PulseRay{};
          continue;
        }
        active[at] = 1;
        rays[at] = PulseRay{Eigen::Vector3d(org[0][i], org[1][i], org[2][i]),
                            Eigen::Vector3d(dir[0][i], dir[1][i], dir[2][i])};
      }
    }
    start = end;
  }
}

}  // namespace owsim
