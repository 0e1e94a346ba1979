#pragma once
// A ROS 2 channel's metadata in an MCAP file (profile `ros2`): `offered_qos_profiles`, the QoS
// its publisher offered, as rosbag2_storage_mcap records it — the YAML rosbag2 writes (one
// profile), with the policies as numbers (rmw's enums), the form both Humble's and Jazzy's
// `ros2 bag play` read. A latched topic (transient_local durability, depth 1) is republished by
// `ros2 bag play` so that late subscribers still receive it, as /tf_static and a scene are meant.
#include <string>
#include <utility>
#include <vector>

namespace owsim::ros2 {

// keep_last, reliable; depth 1 and transient_local when latched, else depth 10 and volatile;
// deadline, lifespan and lease duration 0 (the RMW default: none), liveliness automatic.
[[nodiscard]] std::string offered_qos_profiles(bool latched);
// {{"offered_qos_profiles", offered_qos_profiles(latched)}}.
[[nodiscard]] std::vector<std::pair<std::string, std::string>> channel_metadata(bool latched);

}  // namespace owsim::ros2
