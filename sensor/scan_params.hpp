#pragma once
// Every constant of the MilOWS/HELLAS scan (SENSOR-SPEC §1–3, §8) as one plain struct with the
// spec's defaults. A scenario may override any field; nothing below is hard-coded elsewhere.
#include <cstdint>
#include <vector>

#include "sensor/range_counter.hpp"
#include "sensor/sensor_model.hpp"

namespace owsim {

// Firing order of the fibers within a line (SENSOR-SPEC §2).
enum class FiberOrder {
  crosstalk_resorted,  // default: channels 1→64 (left edge → centre), 65→127 (right edge → centre), 128
  sequential,          // left to right by α, then the reference fiber
};

struct ScanParams {
  SensorModel model = SensorModel::milows;
  double prf_hz = 61'111.0;        // §1/§2 pulse repetition frequency, 128 × 477.43 Hz
  int fibers_per_line = 128;       // §2, the last one is the reference fiber
  int lines_per_frame = 159;       // §2, whole lines in 1/3 s
  double sweep_deg = 36.0;         // §2 mirror sweep per frame, centred on 0 (−18°..+18°)
  double sawtooth_deg = 0.134;     // §2 β_FC magnitude: −on odd fibers, +on even fibers
  double frame_jitter_deg = 0.114248067;  // §2 eq 4.5–4.6 frame-start jitter amplitude
  double look_into_turn_s = 2.0;   // §2 τ of the look-into-turn law (MilOWS only; 0 disables)
  double look_into_turn_limit_deg = 12.0;  // §2 clamp of the sweep-centre shift
  FiberOrder fiber_order = FiberOrder::crosstalk_resorted;
  // α of fibers 1..fibers_per_line−1 in degrees (table 1); empty = the linear default of §2.
  std::vector<double> alpha_table_deg;
  std::uint16_t reference_counts = 10;  // §8 reference-fiber range, counts
  // §8 HELLAS mirror angle factor (MAF), degrees per pulse; 0 = sweep_deg / pulses_per_frame.
  double hellas_mirror_angle_factor_deg = 0.0;
  double start_s = 0.0;            // §2 pinned timing: time of pulse 0 of frame 0
  RangeCounterParams counter;      // §1

  [[nodiscard]] int pulses_per_frame() const { return fibers_per_line * lines_per_frame; }
  [[nodiscard]] int reference_fiber() const { return fibers_per_line; }
  [[nodiscard]] double frame_duration_s() const { return pulses_per_frame() / prf_hz; }
};

}  // namespace owsim
