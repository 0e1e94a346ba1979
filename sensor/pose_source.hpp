#pragma once
// Where the aircraft is at any instant: the one thing the frame simulator asks of a trajectory
// (SENSOR-SPEC §5). Implementations: a spline-interpolated recorded or planned trajectory
// (sensor/trajectory.hpp), or a fixed/straight pose in tests. pose_at must be thread-safe.
#include "sensor/mounting.hpp"

namespace owsim {

class PoseSource {
 public:
  virtual ~PoseSource() = default;
  // The pose at time t (seconds on the trajectory's clock).
  [[nodiscard]] virtual Pose pose_at(double time_s) const = 0;
  // Heading rate in degrees per second at time t, positive turning right (SENSOR-SPEC §2
  // look-into-turn). Default: 0.
  [[nodiscard]] virtual double heading_rate_deg_per_s(double /*time_s*/) const { return 0.0; }
};

// A pose that does not change: a hovering sensor, for tests and benchmarks.
class FixedPose final : public PoseSource {
 public:
  explicit FixedPose(const Pose& pose) : pose_(pose) {}
  [[nodiscard]] Pose pose_at(double time_s) const override {
    Pose pose = pose_;
    pose.time_s = time_s;
    return pose;
  }

 private:
  Pose pose_;
};

}  // namespace owsim
