#pragma once
// flight.mcap (output `mcap`, INTERFACE.md "Robotics output"): MCAP, profile ros2, for Foxglove
// and `ros2 bag play`, and metadata.yaml beside it (rosbag2's bag description, version 5, which
// Humble and later read). Channels, in this order (their ids 1..5):
//   /owsim/points  sensor_msgs/msg/PointCloud2  a frame's returns, frame_id map (local ENU),
//                  fields of io/mcap/lidar_point_cloud.hpp — the frame's rows of points.csv;
//   /tf            tf2_msgs/msg/TFMessage       map → base_link at the frame's start;
//   /owsim/nav     sensor_msgs/msg/NavSatFix    WGS-84 position of base_link at the frame's start,
//                  status FIX (GPS), covariance unknown;
//   /tf_static     tf2_msgs/msg/TFMessage       base_link → owsim_sensor (latched);
//   /owsim/scene   visualization_msgs/msg/MarkerArray  the scene as built (latched,
//                  io/mcap/scene_markers.hpp).
// Axes: map is the scenario's local frame, x east, y north, z up. base_link is the airframe with
// REP-103's axes, x forward, y left, z up (the trajectory's body axes are x forward, y right,
// z down: base_link is that frame turned 180° about x), at the trajectory's position.
// owsim_sensor: x along the boresight (α = β = 0), y left, z up (β grows to the right, α up), at
// the lever arm — the scenario's mount in base_link's axes.
// Time: every message's log and publish time is its header stamp, the frame's start (the latched
// ones: the flight's start, scan.start_s) on the trajectory's clock in nanoseconds. MCAP times are
// unsigned: a flight that starts before time 0 has every stamp shifted by the whole seconds that
// bring its start to 0 (time_offset_s); the points' `time` field stays on the trajectory's clock.
// Layout: a first chunk with the schemas, the channels and the two latched messages, then one
// chunk a frame (its cloud, transform and fix, in that order), zstd: chunks end at frame
// boundaries, so the file's bytes depend only on the frames, never on threads or processes, and
// memory holds a frame at a time. A frame's chunk is built on the pipeline's parallel stage
// (FlightMcapEncoder, into the frame's McapFrameEncoding); the in-order sink only places it.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/mcap/cdr_writer.hpp"
#include "io/mcap/lidar_point_cloud.hpp"
#include "io/mcap/mcap_chunk.hpp"
#include "io/mcap/mcap_writer.hpp"
#include "io/mcap/ros2_messages.hpp"
#include "io/points/point_record.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

// One frame's chunk of flight.mcap and the buffers that build it, reused frame after frame.
struct McapFrameEncoding {
  McapChunk chunk;
  CdrWriter message;
  std::vector<ros2::LidarPoint> points;
  std::vector<unsigned char> packed_points;
};

// The MCAP times of a flight: nanoseconds on the trajectory's clock, shifted by time_offset_s.
class FlightMcapClock {
 public:
  explicit FlightMcapClock(const ScanParams& scan);
  // Whole seconds added to every stamp: 0 unless the flight starts before time 0.
  [[nodiscard]] std::int64_t time_offset_s() const { return offset_s_; }
  // Throws owsim::Error for a time MCAP or ROS 2 cannot hold (before the shifted 0, past 2^31 s).
  [[nodiscard]] std::uint64_t nanoseconds(double time_s) const;
  [[nodiscard]] static ros2::Time stamp(std::uint64_t nanoseconds);

 private:
  std::int64_t offset_s_ = 0;
};

// The frame transforms of flight.mcap (see above).
[[nodiscard]] ros2::TransformStamped map_to_base_link(const Pose& pose, const ros2::Time& stamp);
[[nodiscard]] ros2::TransformStamped base_link_to_sensor(const Mount& mount,
                                                         const ros2::Time& stamp);

// Builds a frame's chunk; const and thread-safe (each call with its own McapFrameEncoding).
class FlightMcapEncoder {
 public:
  // `local_frame` must outlive the encoder.
  FlightMcapEncoder(const ScanParams& scan, const LocalFrame& local_frame);
  // Frame `frame`'s messages (sequence numbers = the frame's index) from its points (as
  // frame_points gives them, the rows of points.csv) and the aircraft's pose at its first pulse.
  void encode(std::int64_t frame, const Pose& frame_start, std::span<const PointRecord> points,
              McapFrameEncoding& out) const;

 private:
  FlightMcapClock clock_;
  const LocalFrame* local_frame_;
};

// flight.mcap and metadata.yaml in `directory`: the first chunk when opened, frame chunks in
// frame order from 0, the summary and metadata.yaml at finish(). Nothing appears under the final
// names before finish().
class FlightMcapFile {
 public:
  FlightMcapFile(const std::filesystem::path& directory, const Scene& scene, const ScanParams& scan,
                 const Mount& mount);
  // A frame's chunk (McapFrameEncoding::chunk, or one another process built and sent). Throws
  // owsim::Error for a frame out of order.
  void append(const McapChunk& frame);
  void finish();

 private:
  std::filesystem::path directory_;
  McapWriter writer_;
  std::uint64_t start_ns_;
  std::uint64_t end_ns_;
  std::vector<std::uint64_t> topic_messages_;  // by channel id − 1
};

}  // namespace owsim
