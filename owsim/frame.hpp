#pragma once
// One simulated frame as an embedding program gets it (INTERFACE.md "Embedding"): the scan
// pattern's pulses, the central ray of each, what the receiver recorded, the sensor's words for
// the frame exactly as `owsim run` writes them into flight.d64 / flight.hellas (the HELLAS file's
// header word excluded), and every detected return as one plain record holding a points.csv row.
// A Frame owns its buffers; Simulation::simulate_frame(k, frame) refills them, so a host that
// keeps one Frame allocates nothing per frame once they have grown.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/frame_simulator.hpp"
#include "geometry/geodesy_cells.hpp"
#include "io/points/point_record.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/sensor_model.hpp"

namespace owsim {

// One detected return: the points.csv columns, in their order, as numbers. Standard layout with
// a fixed size, the same as the C ABI's owsim_return and the Python module's structured dtype.
struct ReturnRecord {
  std::int64_t frame = 0;
  std::int32_t pulse = 0;          // index within the frame, 0-based
  std::int32_t line = 0;           // scan line within the frame
  std::int32_t fiber = 0;          // 1..127
  std::int32_t return_number = 1;  // points.csv `return`: 1 or 2
  double time_s = 0;               // pulse time on the trajectory's clock
  double range_m = 0;              // after noise
  std::uint16_t counter = 0;       // the range counter the word holds
  std::uint8_t surface = 0;        // points.csv `class`: SurfaceClass (0 wire … 3 ground)
  std::uint8_t number_of_returns = 1;
  std::uint32_t object = 0;          // points.csv `object`: index into Simulation::object_ids()
  double e_m = 0, n_m = 0, u_m = 0;  // local East-North-Up from the scenario origin
  double lat_deg = 0, lon_deg = 0, h_m = 0;  // WGS-84
  double energy_rel = 0;                     // ξ_rx/ξ_tx
  double incidence_deg = 0;
};
static_assert(sizeof(ReturnRecord) == 112);

class Frame {
 public:
  [[nodiscard]] std::int64_t index() const { return result_.frame; }
  [[nodiscard]] SensorModel model() const { return model_; }
  [[nodiscard]] const FrameSweep& sweep() const { return result_.sweep; }
  // Firing order, one entry a pulse (reference-fiber pulses included).
  [[nodiscard]] std::span<const Pulse> pulses() const { return result_.pulses; }
  // The central ray of each pulse, local ENU; the reference fiber's is a default ray.
  [[nodiscard]] std::span<const PulseRay> rays() const { return result_.rays; }
  // The receiver's output per pulse (counters, up to two returns with their objects).
  [[nodiscard]] std::span<const PulseReturns> pulse_returns() const { return result_.returns; }
  // Every detected return, in firing order: the frame's points.csv rows.
  [[nodiscard]] std::span<const ReturnRecord> returns() const { return returns_; }
  // The sensor's words, one a pulse: 64-bit for MilOWS (hellas_words() empty), 32-bit for HELLAS
  // (milows_words() empty).
  [[nodiscard]] std::span<const std::uint64_t> milows_words() const { return milows_words_; }
  [[nodiscard]] std::span<const std::uint32_t> hellas_words() const { return hellas_words_; }
  // The words as the file holds them (little-endian; owsim builds only on little-endian hosts).
  [[nodiscard]] std::span<const std::byte> word_bytes() const;
  [[nodiscard]] FrameView view() const { return result_.view(); }

 private:
  friend class Simulation;
  // Words and return records from the simulated result_, in parallel over blocks of pulses (call
  // it inside the Simulation's task arena); the same values as one pass pulse by pulse.
  void encode(const ScanParams& scan, const GeodesyCells& geodesy);

  SensorModel model_ = SensorModel::milows;
  FrameResult result_;
  std::vector<std::uint64_t> milows_words_;
  std::vector<std::uint32_t> hellas_words_;
  std::vector<std::size_t> first_return_;  // pulse k's returns start at returns_[first_return_[k]]
  std::vector<ReturnRecord> returns_;
};

}  // namespace owsim
