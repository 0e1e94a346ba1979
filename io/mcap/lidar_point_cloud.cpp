#include "io/mcap/lidar_point_cloud.hpp"

#include <bit>
#include <utility>

#include "io/files/little_endian.hpp"

namespace owsim::ros2 {

std::vector<PointField> lidar_point_fields() {
  return {{"x", 0, PointField::kFloat64, 1},    {"y", 8, PointField::kFloat64, 1},
          {"z", 16, PointField::kFloat64, 1},   {"intensity", 24, PointField::kFloat32, 1},
          {"ring", 28, PointField::kUint16, 1}, {"return", 30, PointField::kUint8, 1},
          {"class", 31, PointField::kUint8, 1}, {"time", 32, PointField::kFloat64, 1}};
}

void pack_lidar_points(std::span<const LidarPoint> points, std::vector<unsigned char>& data) {
  data.resize(points.size() * kLidarPointStep);
  unsigned char* record = data.data();
  for (const LidarPoint& point : points) {
    store_little_endian(std::bit_cast<std::uint64_t>(point.x), record);
    store_little_endian(std::bit_cast<std::uint64_t>(point.y), record + 8);
    store_little_endian(std::bit_cast<std::uint64_t>(point.z), record + 16);
    store_little_endian(std::bit_cast<std::uint32_t>(point.intensity), record + 24);
    store_little_endian(point.ring, record + 28);
    record[30] = point.return_number;
    record[31] = point.classification;
    store_little_endian(std::bit_cast<std::uint64_t>(point.time), record + 32);
    record += kLidarPointStep;
  }
}

PointCloud2 lidar_point_cloud(Header header, std::span<const unsigned char> data) {
  PointCloud2 cloud;
  cloud.header = std::move(header);
  cloud.height = 1;
  cloud.width = static_cast<std::uint32_t>(data.size() / kLidarPointStep);
  cloud.fields = lidar_point_fields();
  cloud.point_step = kLidarPointStep;
  cloud.row_step = cloud.width * kLidarPointStep;
  cloud.data = data;
  cloud.is_dense = true;
  return cloud;
}

}  // namespace owsim::ros2
