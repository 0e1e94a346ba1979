#pragma once
// The schemas of flight.mcap's messages as rosbag2 writes them (MCAP schema encoding `ros2msg`,
// rosbag2_cpp's LocalMessageDefinitionSource): the type's .msg file, then each type it refers
// to, once, depth first in the sorted order of the names, each after a line of 80 '=' and a line
// `MSG: pkg/Type`. The .msg texts are ROS 2 Jazzy Jalisco's (their fields are Humble's too).
#include <string>
#include <string_view>

namespace owsim::ros2 {

inline constexpr std::string_view kRos2MsgSchemaEncoding = "ros2msg";

// The schema data of `type` ("sensor_msgs/msg/PointCloud2", …: the types of ros2_messages.hpp).
// Throws owsim::Error for another type.
[[nodiscard]] std::string ros2msg_schema(std::string_view type);

}  // namespace owsim::ros2
