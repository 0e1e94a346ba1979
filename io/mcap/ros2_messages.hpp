#pragma once
// The ROS 2 messages flight.mcap carries, as plain structs, and their CDR serialization
// (io/mcap/cdr_writer.hpp). Field names, types and order are those of the ROS 2 Jazzy Jalisco
// definitions (the .msg texts of io/mcap/ros2_msg_definitions.hpp, identical in their fields to
// Humble's): sensor_msgs/msg/PointCloud2 (PointField), sensor_msgs/msg/NavSatFix (NavSatStatus),
// tf2_msgs/msg/TFMessage (geometry_msgs/TransformStamped), visualization_msgs/msg/MarkerArray
// (Marker, with the texture, UV and mesh-file fields), and what they contain.
// serialize() appends a message's fields to `out` (after its encapsulation header: call
// out.clear() first for a new message).
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/mcap/cdr_writer.hpp"

namespace owsim::ros2 {

inline constexpr std::string_view kPointCloud2Type = "sensor_msgs/msg/PointCloud2";
inline constexpr std::string_view kNavSatFixType = "sensor_msgs/msg/NavSatFix";
inline constexpr std::string_view kTfMessageType = "tf2_msgs/msg/TFMessage";
inline constexpr std::string_view kMarkerArrayType = "visualization_msgs/msg/MarkerArray";

struct Time {  // builtin_interfaces/Time
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};
using Duration = Time;  // builtin_interfaces/Duration: the same fields

// Nanoseconds since the clock's epoch as sec + nanosec (sec rounds down, nanosec in 0..999999999).
// Throws owsim::Error when sec leaves the int32 range.
[[nodiscard]] Time time_from_nanoseconds(std::int64_t nanoseconds);

struct Header {  // std_msgs/Header
  Time stamp;
  std::string frame_id;
};

struct Vector3 {  // geometry_msgs/Vector3, also geometry_msgs/Point
  double x = 0, y = 0, z = 0;
};
using Point = Vector3;

struct Quaternion {  // geometry_msgs/Quaternion
  double x = 0, y = 0, z = 0, w = 1;
};

struct Pose {  // geometry_msgs/Pose
  Point position;
  Quaternion orientation;
};

struct Transform {  // geometry_msgs/Transform
  Vector3 translation;
  Quaternion rotation;
};

struct TransformStamped {  // geometry_msgs/TransformStamped
  Header header;
  std::string child_frame_id;
  Transform transform;
};

struct TfMessage {  // tf2_msgs/TFMessage
  std::vector<TransformStamped> transforms;
};

struct PointField {  // sensor_msgs/PointField
  static constexpr std::uint8_t kInt8 = 1, kUint8 = 2, kInt16 = 3, kUint16 = 4, kInt32 = 5,
                                kUint32 = 6, kFloat32 = 7, kFloat64 = 8;
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;
};

struct PointCloud2 {  // sensor_msgs/PointCloud2
  Header header;
  std::uint32_t height = 1;
  std::uint32_t width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0;
  std::uint32_t row_step = 0;
  std::span<const unsigned char> data;  // not owned: the caller's packed points
  bool is_dense = true;
};

struct NavSatStatus {  // sensor_msgs/NavSatStatus
  static constexpr std::int8_t kStatusUnknown = -2, kStatusNoFix = -1, kStatusFix = 0;
  static constexpr std::uint16_t kServiceGps = 1;
  std::int8_t status = kStatusUnknown;
  std::uint16_t service = 0;
};

struct NavSatFix {  // sensor_msgs/NavSatFix
  static constexpr std::uint8_t kCovarianceTypeUnknown = 0, kCovarianceTypeApproximated = 1,
                                kCovarianceTypeDiagonalKnown = 2, kCovarianceTypeKnown = 3;
  Header header;
  NavSatStatus status;
  double latitude = 0, longitude = 0, altitude = 0;  // degrees, degrees, metres above WGS-84
  std::array<double, 9> position_covariance{};
  std::uint8_t position_covariance_type = kCovarianceTypeUnknown;
};

struct ColorRgba {  // std_msgs/ColorRGBA
  float r = 0, g = 0, b = 0, a = 0;
};

struct UvCoordinate {  // visualization_msgs/UVCoordinate
  float u = 0, v = 0;
};

struct CompressedImage {  // sensor_msgs/CompressedImage
  Header header;
  std::string format;
  std::vector<unsigned char> data;
};

struct MeshFile {  // visualization_msgs/MeshFile
  std::string filename;
  std::vector<unsigned char> data;
};

struct Marker {  // visualization_msgs/Marker
  static constexpr std::int32_t kArrow = 0, kCube = 1, kSphere = 2, kCylinder = 3, kLineStrip = 4,
                                kLineList = 5, kCubeList = 6, kSphereList = 7, kPoints = 8,
                                kTextViewFacing = 9, kMeshResource = 10, kTriangleList = 11,
                                kArrowStrip = 12;
  static constexpr std::int32_t kAdd = 0, kDelete = 2, kDeleteAll = 3;
  Header header;
  std::string ns;
  std::int32_t id = 0;
  std::int32_t type = kCube;
  std::int32_t action = kAdd;
  Pose pose;
  Vector3 scale{1, 1, 1};
  ColorRgba color;
  Duration lifetime;  // 0: forever
  bool frame_locked = false;
  std::vector<Point> points;
  std::vector<ColorRgba> colors;
  std::string texture_resource;
  CompressedImage texture;
  std::vector<UvCoordinate> uv_coordinates;
  std::string text;
  std::string mesh_resource;
  MeshFile mesh_file;
  bool mesh_use_embedded_materials = false;
};

struct MarkerArray {  // visualization_msgs/MarkerArray
  std::vector<Marker> markers;
};

void serialize(const PointCloud2& message, CdrWriter& out);
void serialize(const NavSatFix& message, CdrWriter& out);
void serialize(const TfMessage& message, CdrWriter& out);
void serialize(const MarkerArray& message, CdrWriter& out);

}  // namespace owsim::ros2
