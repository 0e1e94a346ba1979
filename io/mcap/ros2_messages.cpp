#include "io/mcap/ros2_messages.hpp"

#include <limits>

#include "geometry/error.hpp"

namespace owsim::ros2 {
namespace {

constexpr std::int64_t kNanosecondsPerSecond = 1'000'000'000;

void put(const Time& time, CdrWriter& out) {
  out.i32(time.sec);
  out.u32(time.nanosec);
}

void put(const Header& header, CdrWriter& out) {
  put(header.stamp, out);
  out.string(header.frame_id);
}

void put(const Vector3& vector, CdrWriter& out) {
  out.f64(vector.x);
  out.f64(vector.y);
  out.f64(vector.z);
}

void put(const Quaternion& rotation, CdrWriter& out) {
  out.f64(rotation.x);
  out.f64(rotation.y);
  out.f64(rotation.z);
  out.f64(rotation.w);
}

void put(const Pose& pose, CdrWriter& out) {
  put(pose.position, out);
  put(pose.orientation, out);
}

void put(const ColorRgba& color, CdrWriter& out) {
  out.f32(color.r);
  out.f32(color.g);
  out.f32(color.b);
  out.f32(color.a);
}

void put(const TransformStamped& transform, CdrWriter& out) {
  put(transform.header, out);
  out.string(transform.child_frame_id);
  put(transform.transform.translation, out);
  put(transform.transform.rotation, out);
}

void put(const PointField& field, CdrWriter& out) {
  out.string(field.name);
  out.u32(field.offset);
  out.u8(field.datatype);
  out.u32(field.count);
}

void put(const Marker& marker, CdrWriter& out) {
  put(marker.header, out);
  out.string(marker.ns);
  out.i32(marker.id);
  out.i32(marker.type);
  out.i32(marker.action);
  put(marker.pose, out);
  put(marker.scale, out);
  put(marker.color, out);
  put(marker.lifetime, out);
  out.boolean(marker.frame_locked);
  out.sequence_size(marker.points.size());
  for (const Point& point : marker.points) put(point, out);
  out.sequence_size(marker.colors.size());
  for (const ColorRgba& color : marker.colors) put(color, out);
  out.string(marker.texture_resource);
  put(marker.texture.header, out);
  out.string(marker.texture.format);
  out.byte_sequence(marker.texture.data);
  out.sequence_size(marker.uv_coordinates.size());
  for (const UvCoordinate& uv : marker.uv_coordinates) {
    out.f32(uv.u);
    out.f32(uv.v);
  }
  out.string(marker.text);
  out.string(marker.mesh_resource);
  out.string(marker.mesh_file.filename);
  out.byte_sequence(marker.mesh_file.data);
  out.boolean(marker.mesh_use_embedded_materials);
}

}  // namespace

Time time_from_nanoseconds(std::int64_t nanoseconds) {
  std::int64_t seconds = nanoseconds / kNanosecondsPerSecond;
  std::int64_t rest = nanoseconds % kNanosecondsPerSecond;
  if (rest < 0) {
    rest += kNanosecondsPerSecond;
    --seconds;
  }
  if (seconds < std::numeric_limits<std::int32_t>::min() ||
      seconds > std::numeric_limits<std::int32_t>::max()) {
    throw Error("time " + std::to_string(nanoseconds) +
                " ns is outside the range of a ROS 2 time (int32 seconds)");
  }
  return {static_cast<std::int32_t>(seconds), static_cast<std::uint32_t>(rest)};
}

void serialize(const PointCloud2& message, CdrWriter& out) {
  put(message.header, out);
  out.u32(message.height);
  out.u32(message.width);
  out.sequence_size(message.fields.size());
  for (const PointField& field : message.fields) put(field, out);
  out.boolean(message.is_bigendian);
  out.u32(message.point_step);
  out.u32(message.row_step);
  out.byte_sequence(message.data);
  out.boolean(message.is_dense);
}

void serialize(const NavSatFix& message, CdrWriter& out) {
  put(message.header, out);
  out.i8(message.status.status);
  out.u16(message.status.service);
  out.f64(message.latitude);
  out.f64(message.longitude);
  out.f64(message.altitude);
  for (const double covariance : message.position_covariance) out.f64(covariance);
  out.u8(message.position_covariance_type);
}

void serialize(const TfMessage& message, CdrWriter& out) {
  out.sequence_size(message.transforms.size());
  for (const TransformStamped& transform : message.transforms) put(transform, out);
}

void serialize(const MarkerArray& message, CdrWriter& out) {
  out.sequence_size(message.markers.size());
  for (const Marker& marker : message.markers) put(marker, out);
}

}  // namespace owsim::ros2
