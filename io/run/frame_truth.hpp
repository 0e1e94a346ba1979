#pragma once
// One frame's ground truth (INTERFACE.md "Ground truth and detection evidence", truth.csv): every
// scene object within the counter's timeout range of the sensor at the frame's middle, or with
// returns in the frame, with its nearest point's range and angles, whether some part of it was in
// the frame's scanned field, its returns and how fast the aircraft closed on it. Computed by
// evaluation/frame_truth.hpp through FrameTruthSource, so the outputs (io/run) need not know how;
// encoded into truth.csv rows by io/run/truth_csv.hpp.
#include <cstdint>
#include <span>
#include <vector>

#include "io/run/flight_summary.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

struct TruthRow {
  std::uint32_t object = 0;  // named object index (geometry/scene.hpp object_ids order)
  double range_m = 0.0;      // of the nearest point: in the field when in_view, else overall
  double alpha_deg = 0.0;    // that point's α and β in the sensor frame (SENSOR-SPEC §4)
  double beta_deg = 0.0;
  bool in_view = false;
  std::uint64_t returns = 0;       // the object's returns in the frame (first and second)
  double closing_speed_mps = 0.0;  // −d(range)/dt of that point; negative when opening
};

struct FrameTruth {
  std::int64_t frame = -1;
  double time_s = 0.0;         // the frame's middle, where the rows' geometry is taken
  std::vector<TruthRow> rows;  // by object index
};

// Computes a frame's truth; const and thread-safe (frames are encoded in parallel).
class FrameTruthSource {
 public:
  virtual ~FrameTruthSource() = default;
  // The truth of `frame`, whose sweep is `sweep` and whose returns on scene objects are `hits`.
  virtual void frame_truth(std::int64_t frame, const FrameSweep& sweep,
                           std::span<const FrameTally::ObjectHit> hits, FrameTruth& out) const = 0;
};

}  // namespace owsim
