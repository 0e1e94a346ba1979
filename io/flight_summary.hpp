#pragma once
// summary.json of `owsim run` (INTERFACE.md): totals of the flight and, per scenario object (each
// conductor on its own), when and from how far the sensor first saw it — the ground truth that
// obstacle-detection software is scored against. Fed one frame at a time, in frame order.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

struct ObjectTruth {
  std::string id;
  SurfaceClass surface = SurfaceClass::wire;
  std::uint64_t returns = 0;
  std::uint64_t frames_seen = 0;
  std::optional<double> first_seen_s;
  std::optional<double> first_seen_range_m;  // the true range of the first return on it
  std::optional<double> min_range_m;
  std::int64_t last_frame_seen = -1;
};

class FlightSummary {
 public:
  // One entry per scene object, in object-index order (conductors, then cylinders).
  explicit FlightSummary(const Scene& scene);

  // Adds one frame's returns (frames must come in order).
  void add_frame(std::int64_t frame, std::span<const Pulse> pulses,
                 std::span<const PulseReturns> returns);

  [[nodiscard]] const std::vector<ObjectTruth>& objects() const { return objects_; }
  [[nodiscard]] std::uint64_t frames() const { return frames_; }
  [[nodiscard]] std::uint64_t pulses() const { return pulses_; }
  [[nodiscard]] std::uint64_t returns_of(SurfaceClass surface) const {
    return returns_by_class_[static_cast<std::size_t>(surface)];
  }
  [[nodiscard]] std::uint64_t second_returns() const { return second_returns_; }

  // Everything of INTERFACE.md's summary.json that the frames determine; the caller adds run
  // facts (scenario, seed, wall time, threads, version).
  [[nodiscard]] nlohmann::json to_json() const;

 private:
  std::vector<ObjectTruth> objects_;
  std::uint64_t frames_ = 0;
  std::uint64_t pulses_ = 0;
  std::uint64_t returns_by_class_[4] = {0, 0, 0, 0};
  std::uint64_t second_returns_ = 0;
};

}  // namespace owsim
