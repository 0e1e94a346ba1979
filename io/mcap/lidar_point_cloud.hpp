#pragma once
// The points of /owsim/points (issue 47, INTERFACE.md "Robotics output"): one sensor_msgs/
// PointCloud2 point per return, 40 bytes little-endian, fields in this order:
//   x, y, z    FLOAT64 at 0, 8, 16   local East-North-Up metres (frame `map`)
//   intensity  FLOAT32 at 24         energy_rel
//   ring       UINT16  at 28         the fiber
//   return     UINT8   at 30         the return number
//   class      UINT8   at 31         the LAS class
//   time       FLOAT64 at 32         the pulse's time, seconds on the trajectory's clock
#include <cstdint>
#include <span>
#include <vector>

#include "io/mcap/ros2_messages.hpp"

namespace owsim::ros2 {

inline constexpr std::uint32_t kLidarPointStep = 40;

struct LidarPoint {
  double x = 0, y = 0, z = 0;
  float intensity = 0;
  std::uint16_t ring = 0;
  std::uint8_t return_number = 0;
  std::uint8_t classification = 0;
  double time = 0;
};

// The PointFields above.
[[nodiscard]] std::vector<PointField> lidar_point_fields();
// Replaces `data` with the points' 40-byte records.
void pack_lidar_points(std::span<const LidarPoint> points, std::vector<unsigned char>& data);
// A one-row cloud of `data` (packed points, still owned by the caller) with the fields above.
[[nodiscard]] PointCloud2 lidar_point_cloud(Header header, std::span<const unsigned char> data);

}  // namespace owsim::ros2
